# R's own accuracy on the NIST StRD univariate sets (and one-way ANOVA sets), for
# tests/stats/test_nist.cpp: feint must be at least as accurate as R on every set.
# Regenerate (from the repository root, with ../shared beside it):
#   Rscript tests/golden/stats/nist_r.R ../shared/nist-strd tests/golden/stats
# R reads the CSV text into doubles (read.csv), as any program parsing the numbers would.
args <- commandArgs(trailingOnly = TRUE)
nist <- if (length(args) >= 1) args[1] else "../shared/nist-strd"
out <- if (length(args) >= 2) args[2] else "tests/golden/stats"
cert <- read.csv(file.path(nist, "certified.csv"), colClasses = c("character", "character",
                                                                   "character", "character"))
certified <- function(set, q) as.numeric(cert$certified_value[cert$dataset == set & cert$quantity == q])
lre <- function(x, c) {
  if (!is.finite(x)) return(0)
  e <- if (c == 0) abs(x) else abs(x - c) / abs(c)
  if (e == 0) return(15)
  min(15, -log10(e))
}
g <- function(x) sprintf("%.17g", x)

uni <- c("Lew", "Lottery", "Mavro", "Michelso", "NumAcc1", "NumAcc2", "NumAcc3", "NumAcc4")
rows <- lapply(uni, function(set) {
  y <- read.csv(file.path(nist, paste0(set, ".csv")))$y
  m <- mean(y); s <- sd(y)
  r1 <- acf(y, lag.max = 1, plot = FALSE, demean = TRUE)$acf[2]
  data.frame(dataset = set, mean = g(m), sd = g(s), autocorr_lag1 = g(r1),
             lre_mean = g(lre(m, certified(set, "mean"))), lre_sd = g(lre(s, certified(set, "sd"))),
             lre_autocorr_lag1 = g(lre(r1, certified(set, "autocorr_lag1"))))
})
write.csv(do.call(rbind, rows), file.path(out, "nist_r_univariate.csv"), row.names = FALSE,
          quote = FALSE)

anova_sets <- c("SiRstv", "AtmWtAg", sprintf("SmLs%02d", 1:9))
rows <- lapply(anova_sets, function(set) {
  d <- read.csv(file.path(nist, paste0(set, ".csv")))
  a <- anova(lm(y ~ factor(group), data = d))
  f <- a[["F value"]][1]
  ssb <- a[["Sum Sq"]][1]; ssw <- a[["Sum Sq"]][2]
  data.frame(dataset = set, f_statistic = g(f), ss_between = g(ssb), ss_within = g(ssw),
             lre_f = g(lre(f, certified(set, "f_statistic"))),
             lre_ss_between = g(lre(ssb, certified(set, "ss_between"))),
             lre_ss_within = g(lre(ssw, certified(set, "ss_within"))))
})
write.csv(do.call(rbind, rows), file.path(out, "nist_r_anova.csv"), row.names = FALSE, quote = FALSE)
