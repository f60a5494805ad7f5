# R reference values for tests/cli/test_report_agrees.cpp (OneSided.*): the questionnaire of the
# test's small study, adaptive (A) against random (B), tested one-sided (alternative = "greater",
# a confirmatory H2 with direction greater) and two-sided (the exploratory default).
# Run: Rscript tests/cli/one_sided_golden.R   (R 4.2.2, BayesFactor 0.9.12-4.4)
suppressMessages(library(BayesFactor))
items <- list(
  trust  = list(a = c(5, 6, 4, 7, 5, 6, 5, 4, 6, 7), b = c(4, 3, 5, 4, 2, 5, 4, 3, 4, 5)),
  warmth = list(a = c(3, 4, 4, 5, 3, 4, 5, 4, 3, 4), b = c(4, 4, 3, 5, 4, 4, 3, 5, 4, 4)))
for (name in names(items)) {
  a <- items[[name]]$a; b <- items[[name]]$b
  for (alt in c("greater", "two.sided")) {
    t <- t.test(a, b, alternative = alt)  # Welch
    w <- suppressWarnings(wilcox.test(a, b, alternative = alt, exact = FALSE, correct = TRUE))
    # Equal group sizes: the Welch t equals the pooled t that ttestBF uses.
    ni <- if (alt == "greater") c(0, Inf) else NULL
    bf <- extractBF(ttestBF(a, b, nullInterval = ni, rscale = sqrt(2) / 2))$bf[1]
    cat(sprintf("%s %s: t p = %.12g, conf.low = %.12g, conf.high = %.12g, W = %g, W p = %.12g, BF10 = %.12g\n",
                name, alt, t$p.value, t$conf.int[1], t$conf.int[2], w$statistic, w$p.value, bf))
  }
}
