# Golden values for feint's yes/no statistics (tests/stats/test_proportions.cpp): binom.test's
# Clopper-Pearson interval, prop.test's Wilson interval (one sample, correct = FALSE), and the two
# conditions compared by fisher.test and prop.test (with and without the continuity correction).
# Regenerate from the repository root with
#   Rscript tests/golden/yesno/make_yesno_golden.R
# Needs base R only (R >= 4.2). Numbers are written with sprintf("%.17g"). fisher.test's odds ratio
# and interval come from uniroot at its default tol (1.2e-4): they are R's numbers, not the exact
# roots; the test checks feint's exact roots against them at that tolerance and against the
# defining equations at 1e-10.
out_dir <- "tests/golden/yesno"
if (!dir.exists(out_dir)) stop("run from the repository root")
g17 <- function(v) ifelse(is.na(v), "NA", sprintf("%.17g", v))

one <- expand.grid(x = c(0, 1, 3, 7, 12, 20), n = c(20, 31), conf = c(0.95, 0.9))
one <- one[one$x <= one$n, ]
one_rows <- apply(one, 1, function(r) {
  b <- binom.test(r[["x"]], r[["n"]], conf.level = r[["conf"]])$conf.int
  w <- suppressWarnings(prop.test(r[["x"]], r[["n"]], conf.level = r[["conf"]], correct = FALSE))$conf.int
  paste(g17(c(r[["x"]], r[["n"]], r[["conf"]], b[1], b[2], w[1], w[2])), collapse = ",")
})
writeLines(c("x,n,conf_level,exact_low,exact_high,wilson_low,wilson_high", one_rows),
           file.path(out_dir, "proportion.csv"))

# Two conditions: yes1 of n1 against yes2 of n2, including the ends of the support, a table with
# a tiny p-value (< 1e-6), small expected counts and unequal sizes.
tables <- rbind(c(12, 20, 5, 20), c(3, 15, 9, 14), c(0, 10, 6, 12), c(10, 10, 4, 11),
                c(18, 30, 17, 29), c(1, 40, 35, 40), c(7, 9, 1, 8), c(25, 60, 33, 55),
                c(2, 5, 2, 5), c(50, 200, 80, 190), c(4, 4, 0, 4))
rows <- character(0)
for (i in seq_len(nrow(tables))) {
  t <- tables[i, ]
  m <- matrix(c(t[1], t[3], t[2] - t[1], t[4] - t[3]), 2)
  for (alt in c("two.sided", "less", "greater")) for (conf in c(0.95, 0.9)) {
    f <- fisher.test(m, alternative = alt, conf.level = conf)
    for (correct in c(TRUE, FALSE)) {
      p <- suppressWarnings(prop.test(c(t[1], t[3]), c(t[2], t[4]), alternative = alt,
                                      conf.level = conf, correct = correct))
      rows <- c(rows, paste(c(g17(c(t, conf)), alt, if (correct) "TRUE" else "FALSE",
        g17(c(f$p.value, f$estimate, f$conf.int[1], f$conf.int[2], p$statistic, p$p.value,
              p$conf.int[1], p$conf.int[2]))), collapse = ","))
    }
  }
}
writeLines(c(paste("yes1,n1,yes2,n2,conf_level,alternative,correct,fisher_p,fisher_or,fisher_low,",
                   "fisher_high,x2,prop_p,prop_low,prop_high", sep = ""), rows),
           file.path(out_dir, "two_conditions.csv"))
cat(R.version.string, "\n")
