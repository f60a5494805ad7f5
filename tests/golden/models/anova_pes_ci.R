# Partial eta squared with its interval for every effect of the ANOVA goldens:
# effectsize::F_to_eta2 on the table afex reports (GG-corrected df where afex corrects), with its
# default one-sided ("greater") 95 % interval, as feint anova's pes_low / pes_high.
# Run from the project root: Rscript tests/golden/models/anova_pes_ci.R
suppressMessages(library(effectsize))
g <- read.csv("tests/golden/models/anova_golden.csv", stringsAsFactors = FALSE)
out <- do.call(rbind, lapply(seq_len(nrow(g)), function(i) {
  r <- g[i, ]
  e <- F_to_eta2(r$F, r$afex_gg_num_df, r$afex_gg_den_df, ci = 0.95)
  data.frame(case = r$case, effect = r$effect, pes = e$Eta2_partial, pes_low = e$CI_low,
             pes_high = e$CI_high)
}))
write.csv(out, "tests/golden/models/anova_pes_ci.csv", row.names = FALSE, quote = FALSE)
