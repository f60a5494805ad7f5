# Partial eta squared with its interval for every effect of the ANOVA goldens:
# effectsize::F_to_eta2 on the table afex reports (GG-corrected df where afex corrects), with its
# default one-sided ("greater") 95 % interval, as feint anova's pes_low / pes_high; and the exact
# lower bound (pes_low_exact): the root of pf(F, df1, df2, ncp) = 0.95 by uniroot(tol = 1e-15),
# ncp / (ncp + df2), 0 when F <= qf(0.95, df1, df2). effectsize's own bound comes from a search
# and is off by up to ~5e-5 (docs/effect-sizes.md); feint is checked against the exact one.
# Run from the project root: Rscript tests/golden/models/anova_pes_ci.R
suppressMessages(library(effectsize))
g <- read.csv("tests/golden/models/anova_golden.csv", stringsAsFactors = FALSE)
exact_low <- function(f, df1, df2, level = 0.95) {
  if (f <= qf(level, df1, df2)) return(0)
  h <- function(ncp) pf(f, df1, df2, ncp) - level
  hi <- max(10, 2 * f * df1)
  while (h(hi) > 0) hi <- hi * 2
  ncp <- uniroot(h, c(0, hi), tol = 1e-15)$root
  ncp / (ncp + df2)
}
g17 <- function(x) sprintf("%.17g", x)
out <- do.call(rbind, lapply(seq_len(nrow(g)), function(i) {
  r <- g[i, ]
  e <- F_to_eta2(r$F, r$afex_gg_num_df, r$afex_gg_den_df, ci = 0.95)
  data.frame(case = r$case, effect = r$effect, pes = g17(e$Eta2_partial), pes_low = g17(e$CI_low),
             pes_high = g17(e$CI_high),
             pes_low_exact = g17(exact_low(r$F, r$afex_gg_num_df, r$afex_gg_den_df)))
}))
write.csv(out, "tests/golden/models/anova_pes_ci.csv", row.names = FALSE, quote = FALSE)
