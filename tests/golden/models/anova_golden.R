# Golden values of the mixed ANOVA (condition between x iteration within) from afex::aov_ez and
# car::summary.Anova.mlm. Run from the repository root:
#   Rscript tests/golden/models/anova_golden.R
# Writes tests/golden/models/anova_data.csv (the long data of every case) and anova_golden.csv.
# Versions used: R 4.2, afex 1.2-1, car 3.1-1 (Debian 12).
suppressPackageStartupMessages(library(afex))
options(digits = 17)
set.seed(20261123)

make_case <- function(name, n_per_group, k, rho = 0, ar = FALSE, hetero = FALSE, shift = 0,
                      interaction = 0, missing = 0) {
  rows <- list()
  pid <- 0
  for (g in seq_along(n_per_group)) {
    cond <- c("adaptive", "random", "third")[g]
    for (i in seq_len(n_per_group[g])) {
      pid <- pid + 1
      u <- rnorm(1, 0, sqrt(rho))
      e <- rnorm(k)
      if (ar) e <- as.numeric(stats::filter(e, 0.8, method = "recursive"))
      if (hetero) e <- e * seq(0.3, 2, length.out = k)
      it <- seq_len(k)
      mu <- 0.5 + shift * (g - 1) + interaction * (g - 1) * (it - 1) / k - 0.01 * it
      y <- mu + u + 0.1 * e
      rows[[pid]] <- data.frame(case = name, participant = sprintf("P%02d", pid), condition = cond,
                                iteration = it, value = round(y, 6))
    }
  }
  d <- do.call(rbind, rows)
  if (missing > 0) d$value[sample(nrow(d), missing)] <- NA
  d
}

cases <- list(
  make_case("balanced_spherical", c(10, 10), 4),
  make_case("unbalanced_nonspherical", c(7, 12), 5, rho = 0.5, ar = TRUE, hetero = TRUE,
            interaction = 0.3),
  make_case("missing_trials", c(9, 8), 3, rho = 0.2, missing = 3),
  make_case("two_iterations", c(6, 9), 2, rho = 0.3, shift = 0.1),
  make_case("paper_design", c(30, 30), 20, rho = 0.4, ar = TRUE, interaction = 0.2),
  make_case("one_way", c(12), 6, rho = 0.3, hetero = TRUE),
  make_case("singular", c(6, 6), 20, rho = 0.2),
  make_case("three_conditions", c(5, 8, 6), 4, rho = 0.2, hetero = TRUE, shift = 0.05)
)
data <- do.call(rbind, cases)
write.csv(data, "tests/golden/models/anova_data.csv", row.names = FALSE, na = "", quote = FALSE)

out <- list()
for (d in cases) {
  name <- d$case[1]
  d$iteration <- factor(d$iteration)
  one_way <- length(unique(d$condition)) == 1
  fit <- suppressWarnings(suppressMessages(
    if (one_way) aov_ez("participant", "value", d, within = "iteration")
    else aov_ez("participant", "value", d, between = "condition", within = "iteration")))
  s <- suppressWarnings(summary(fit$Anova, multivariate = FALSE))
  uni <- s$univariate.tests
  adj <- s$pval.adjustments
  sph <- s$sphericity.tests
  tab_gg <- suppressWarnings(anova(fit, es = c("ges", "pes"), correction = "GG"))
  tab_hf <- suppressWarnings(anova(fit, es = c("ges", "pes"), correction = "HF"))
  excluded <- attr(fit, "incomplete_cases")
  for (eff in rownames(tab_gg)) {
    get <- function(m, row, col) if (!is.null(m) && row %in% rownames(m) && col %in% colnames(m)) m[row, col] else NA
    out[[length(out) + 1]] <- data.frame(
      case = name, effect = eff, n = length(unique(d$participant)) - length(excluded),
      excluded = paste(excluded, collapse = ";"),
      ss = uni[eff, "Sum Sq"], num_df = uni[eff, "num Df"], error_ss = uni[eff, "Error SS"],
      den_df = uni[eff, "den Df"], F = uni[eff, "F value"], p = uni[eff, "Pr(>F)"],
      gg_eps = get(adj, eff, "GG eps"), p_gg = get(adj, eff, "Pr(>F[GG])"),
      hf_eps = get(adj, eff, "HF eps"), p_hf = get(adj, eff, "Pr(>F[HF])"),
      mauchly_w = get(sph, eff, "Test statistic"), mauchly_p = get(sph, eff, "p-value"),
      afex_gg_num_df = tab_gg[eff, "num Df"], afex_gg_den_df = tab_gg[eff, "den Df"],
      afex_gg_mse = tab_gg[eff, "MSE"], afex_gg_p = tab_gg[eff, "Pr(>F)"],
      afex_hf_den_df = tab_hf[eff, "den Df"], afex_hf_p = tab_hf[eff, "Pr(>F)"],
      ges = tab_gg[eff, "ges"], pes = tab_gg[eff, "pes"])
  }
}
res <- do.call(rbind, out)
print(res[, c("case", "effect", "F", "p", "gg_eps", "hf_eps", "mauchly_w", "ges")])
num <- vapply(res, is.numeric, TRUE)
res[num] <- lapply(res[num], function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x)))
write.csv(res, "tests/golden/models/anova_golden.csv", row.names = FALSE, quote = FALSE)
