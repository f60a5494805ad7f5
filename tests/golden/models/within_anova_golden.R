# Golden values of the repeated-measures ANOVA with condition AND iteration within participants,
# from afex::aov_ez(within = c("condition", "iteration")) and car::summary.Anova.mlm. Run from the
# repository root:
#   Rscript tests/golden/models/within_anova_golden.R
# Writes tests/golden/models/within_anova_data.csv (the long data of every data set) and
# within_anova_golden.csv. Versions used: R 4.2, afex 1.2-1, car 3.1-1 (Debian 12).
suppressPackageStartupMessages(library(afex))
options(digits = 17)
set.seed(20261127)

# Every participant sees every condition at every iteration. `sd_by_condition` scales the trial
# noise per condition (sphericity violated when they differ); `missing` values are set to NA and
# `dropped` rows removed (afex drops those participants: incomplete cases).
make_set <- function(name, n, a, k, rho = 0.3, shift = 0, trend = 0.01, interaction = 0,
                     sd_by_condition = rep(1, a), missing = 0, dropped = 0) {
  rows <- list()
  for (i in seq_len(n)) {
    u <- rnorm(1, 0, sqrt(rho))
    uc <- rnorm(a, 0, 0.05)  # participant x condition variation
    for (cc in seq_len(a)) {
      it <- seq_len(k)
      mu <- 0.5 + shift * (cc - 1) - trend * it + interaction * (cc - 1) * (it - 1) / k
      y <- mu + u + uc[cc] + 0.1 * sd_by_condition[cc] * rnorm(k)
      rows[[length(rows) + 1]] <- data.frame(
        dataset = name, participant = sprintf("P%02d", i),
        condition = c("honest", "deceptive", "random")[cc], iteration = it, y = round(y, 6))
    }
  }
  d <- do.call(rbind, rows)
  if (missing > 0) d$y[sample(nrow(d), missing)] <- NA
  if (dropped > 0) d <- d[-sample(nrow(d), dropped), ]
  d
}

sets <- list(
  make_set("balanced_2x5", 12, 2, 5, shift = 0.05, interaction = 0.1),
  make_set("three_by_four", 10, 3, 4, shift = 0.03, interaction = 0.05),
  make_set("two_by_two", 8, 2, 2, shift = 0.08),
  make_set("missing_trials", 14, 2, 3, shift = 0.02, missing = 3, dropped = 1),
  make_set("nonspherical", 15, 3, 5, sd_by_condition = c(0.3, 1, 6), interaction = 0.2),
  make_set("three_participants", 3, 3, 3, shift = 0.1)
)
data <- do.call(rbind, sets)
write.csv(data, "tests/golden/models/within_anova_data.csv", row.names = FALSE, na = "",
          quote = FALSE)

out <- list()
for (d in sets) {
  name <- d$dataset[1]
  d$condition <- factor(d$condition, levels = unique(d$condition))
  d$iteration <- factor(d$iteration)
  fit <- suppressWarnings(suppressMessages(aov_ez(
    "participant", "y", d, within = c("condition", "iteration"),
    anova_table = list(correction = "none", es = c("ges", "pes")))))
  s <- suppressWarnings(summary(fit$Anova, multivariate = FALSE))
  uni <- s$univariate.tests
  adj <- s$pval.adjustments
  sph <- s$sphericity.tests
  tab <- fit$anova_table
  tab_gg <- suppressWarnings(anova(fit, es = c("ges", "pes"), correction = "GG"))
  tab_hf <- suppressWarnings(anova(fit, es = c("ges", "pes"), correction = "HF"))
  excluded <- attr(fit, "incomplete_cases")
  get <- function(m, row, col) {
    if (!is.null(m) && row %in% rownames(m) && col %in% colnames(m)) m[row, col] else NA
  }
  for (eff in rownames(tab)) {
    gg <- get(adj, eff, "GG eps")
    out[[length(out) + 1]] <- data.frame(
      dataset = name, effect = eff, n = length(unique(d$participant)) - length(excluded),
      excluded = paste(excluded, collapse = ";"),
      ss = uni[eff, "Sum Sq"], error_ss = uni[eff, "Error SS"],
      num_df = tab[eff, "num Df"], den_df = tab[eff, "den Df"], F = tab[eff, "F"],
      p = tab[eff, "Pr(>F)"], ges = tab[eff, "ges"], pes = tab[eff, "pes"], MSE = tab[eff, "MSE"],
      gg_eps = gg, hf_eps = get(adj, eff, "HF eps"),
      p_gg = if (is.na(gg)) NA else get(adj, eff, "Pr(>F[GG])"),
      p_hf = if (is.na(gg)) NA else get(adj, eff, "Pr(>F[HF])"),
      mauchly_w = get(sph, eff, "Test statistic"), mauchly_p = get(sph, eff, "p-value"),
      gg_num_df = tab_gg[eff, "num Df"], gg_den_df = tab_gg[eff, "den Df"],
      gg_mse = tab_gg[eff, "MSE"], gg_p = tab_gg[eff, "Pr(>F)"],
      hf_num_df = tab_hf[eff, "num Df"], hf_den_df = tab_hf[eff, "den Df"],
      hf_mse = tab_hf[eff, "MSE"], hf_p = tab_hf[eff, "Pr(>F)"])
  }
}
res <- do.call(rbind, out)
print(res[, c("dataset", "effect", "n", "F", "p", "gg_eps", "hf_eps", "mauchly_w", "ges")])
num <- vapply(res, is.numeric, TRUE)
res[num] <- lapply(res[num], function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x)))
write.csv(res, "tests/golden/models/within_anova_golden.csv", row.names = FALSE, quote = FALSE)
