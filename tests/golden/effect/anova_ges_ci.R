# Generalized eta squared with its interval for every effect of the mixed-ANOVA goldens
# as effectsize::eta_squared(model, generalized = TRUE) defines it on an afex model, and
# the exact roots of that definition. Run from the project root:
#   Rscript tests/golden/effect/anova_ges_ci.R
# Writes tests/golden/effect/anova_ges_data.csv (the long data of every case: effects strong enough
# that most lower bounds are above 0) and tests/golden/effect/anova_ges_ci.csv.
#
# effectsize 0.8.3 (.anova_es.Anova.mlm -> .es_aov_strata): ges = SS / (SS + sum of every error
# stratum's SS) (all factors manipulated), then the interval of the pseudo-F
#   F* = (ges / df1) / ((1 - ges) / df2),  df1 = the effect's num Df, df2 = its stratum's den Df
# (car's univariate table: UNcorrected for sphericity), by F_to_eta2(F*, df1, df2): one-sided
# ("greater"), the lower bound from the 90 % two-sided noncentral-F interval, the upper bound 1.
# effectsize finds the noncentrality with optim(); the exact root here is uniroot(tol = 1e-15) of
#   pf(F*, df1, df2, ncp) = 0.95,  lower = ncp / (ncp + df2),  0 when F* <= qf(0.95, df1, df2).
suppressPackageStartupMessages({
  library(afex)
  library(effectsize)
})
options(digits = 17)
set.seed(20261126)
make_case <- function(name, n_per_group, k, rho = 0.3, ar = 0, shift = 0, trend = 0,
                      interaction = 0, sd = 0.1) {
  rows <- list()
  pid <- 0
  for (g in seq_along(n_per_group)) {
    for (i in seq_len(n_per_group[g])) {
      pid <- pid + 1
      e <- rnorm(k)
      if (ar > 0) e <- as.numeric(stats::filter(e, ar, method = "recursive"))
      it <- seq_len(k)
      y <- 0.5 + shift * (g - 1) + trend * (it - 1) / k + interaction * (g - 1) * (it - 1) / k +
        rnorm(1, 0, sqrt(rho)) * 0.1 + sd * e
      rows[[pid]] <- data.frame(case = name, participant = sprintf("P%03d", pid),
                                condition = c("adaptive", "random", "third")[g], iteration = it,
                                value = round(y, 6))
    }
  }
  do.call(rbind, rows)
}
data <- rbind(
  make_case("strong_condition", c(10, 10), 4, shift = 0.3),
  make_case("strong_trend_ar", c(7, 12), 5, ar = 0.6, trend = 0.4, interaction = 0.3),
  make_case("paper_design", c(30, 30), 20, ar = 0.5, shift = 0.08, trend = 0.2, interaction = 0.15),
  make_case("small_effects", c(8, 8), 3, shift = 0.02, trend = 0.02),
  make_case("one_way", c(12), 6, trend = 0.5),
  make_case("three_conditions", c(5, 8, 6), 4, shift = 0.1, trend = 0.2, interaction = 0.2),
  make_case("two_iterations", c(6, 9), 2, shift = 0.2, trend = 0.2),
  make_case("n3_per_group", c(3, 3), 3, shift = 0.5, trend = 0.5, sd = 0.2)
)
write.csv(data, "tests/golden/effect/anova_ges_data.csv", row.names = FALSE, quote = FALSE)
exact_low <- function(f, df1, df2, level = 0.95) {
  if (f <= qf(level, df1, df2)) return(0)
  g <- function(ncp) pf(f, df1, df2, ncp) - level
  hi <- max(10, 2 * f * df1)
  while (g(hi) > 0) hi <- hi * 2
  ncp <- uniroot(g, c(0, hi), tol = 1e-15)$root
  ncp / (ncp + df2)
}
out <- list()
for (name in unique(data$case)) {
  d <- data[data$case == name, ]
  d$iteration <- factor(d$iteration)
  one_way <- length(unique(d$condition)) == 1
  fit <- suppressWarnings(suppressMessages(
    if (one_way) aov_ez("participant", "value", d, within = "iteration")
    else aov_ez("participant", "value", d, between = "condition", within = "iteration")))
  uni <- suppressWarnings(summary(fit$Anova, multivariate = FALSE))$univariate.tests
  es <- suppressWarnings(eta_squared(fit, generalized = TRUE, ci = 0.95))
  afex_ges <- suppressWarnings(anova(fit, es = "ges", correction = "none"))
  for (i in seq_len(nrow(es))) {
    eff <- es$Parameter[i]
    df1 <- uni[eff, "num Df"]
    df2 <- uni[eff, "den Df"]
    ges <- es$Eta2_generalized[i]
    f_star <- (ges / df1) / ((1 - ges) / df2)
    out[[length(out) + 1]] <- data.frame(
      case = name, effect = eff, ges = ges, afex_ges = afex_ges[eff, "ges"], df1 = df1, df2 = df2,
      f_star = f_star, ges_low = exact_low(f_star, df1, df2), ges_high = 1,
      es_low = es$CI_low[i], es_high = es$CI_high[i])
  }
}
res <- do.call(rbind, out)
print(res[, c("case", "effect", "ges", "df1", "df2", "ges_low", "es_low")])
cat("max |ges - afex ges|:", max(abs(res$ges - res$afex_ges)), "\n")
cat("max |effectsize low - exact low|:", max(abs(res$es_low - res$ges_low)), "\n")
# Every number with 17 significant digits (write.csv keeps 15, which would cap the agreement).
num <- vapply(res, is.numeric, TRUE)
res[num] <- lapply(res[num], function(x) sprintf("%.17g", x))
write.csv(res, "tests/golden/effect/anova_ges_ci.csv", row.names = FALSE, quote = FALSE)
