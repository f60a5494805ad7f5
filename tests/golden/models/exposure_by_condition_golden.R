# Golden exposure slopes split by condition (tests/models/test_exposure_by_condition.cpp), by the
# participant-level two-stage ("slopes as outcomes") method of models::exposure_slopes_by_condition.
# Regenerate from tests/golden/models with R 4.2 (BayesFactor for the cross-check only):
#   cd tests/golden/models && Rscript exposure_by_condition_golden.R
# Data: lmm_exposure.csv (2 conditions x 3 strategies); exposure = number of the participant's
# earlier trials of the same strategy.
#  stage 1: coef(lm(error ~ exposure)) per participant x strategy over its trials; a participant
#    counts only with >= 2 trials at >= 2 distinct exposures (else "left_out").
#  stage 2: per condition and strategy, t.test(slopes) (one-sample, against 0); the difference
#    adaptive - random = t.test(slopes_a, slopes_r) (Welch), with the JZS Bayes factor (r = sqrt(2)/2)
#    of the pooled two-sample model (t = d sqrt(N), N = n1 n2 / (n1 + n2), nu = n1 + n2 - 2, d with
#    the pooled sd), integrated exactly by log_bf_point() of tests/golden/bayes/make_bf_golden.R;
#    ttestBF's value is a cross-check column.
suppressMessages(library(BayesFactor))
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
tol <- 1e-12
# log_bf_point() of tests/golden/bayes/make_bf_golden.R, taken from that script without running it.
for (e in parse("../bayes/make_bf_golden.R"))
  if (is.call(e) && identical(e[[1]], as.name("<-")) && identical(e[[2]], as.name("log_bf_point"))) eval(e)
stopifnot(exists("log_bf_point"))

d <- read.csv("lmm_exposure.csv")
d <- d[order(d$participant, d$iteration), ]
d$exposure <- ave(seq_len(nrow(d)), d$participant, d$strategy, FUN = seq_along) - 1
strategies <- sort(unique(d$strategy)); conditions <- sort(unique(d$condition))
stage1 <- function(cond, s) {
  dc <- d[d$condition == cond & d$strategy == s & is.finite(d$error), ]
  b <- c(); left <- 0
  for (p in sort(unique(d$participant[d$condition == cond & d$strategy == s]))) {
    dp <- dc[dc$participant == p, ]
    if (nrow(dp) >= 2 && length(unique(dp$exposure)) >= 2) b <- c(b, coef(lm(error ~ exposure, dp))[["exposure"]])
    else left <- left + 1
  }
  list(b = b, left = left)
}
row <- function(kind, s, cond, tt, n, left, lbf = NA, lbf_check = NA)
  data.frame(kind = kind, strategy = s, condition = cond, n = n, left_out = left,
             estimate = g17(if (kind == "slope") tt$estimate[[1]] else tt$estimate[[1]] - tt$estimate[[2]]),
             se = g17(tt$stderr), df = g17(tt$parameter[[1]]), t = g17(tt$statistic[[1]]),
             p = g17(tt$p.value), lower = g17(tt$conf.int[1]), upper = g17(tt$conf.int[2]),
             log_bf10 = g17(lbf), ttestbf_log_bf = g17(lbf_check))
st <- list(); rows <- list()
for (cond in conditions) for (s in strategies) {
  st[[paste(cond, s)]] <- r <- stage1(cond, s)
  rows[[length(rows) + 1]] <- row("slope", s, cond, t.test(r$b), length(r$b), r$left)
}
for (s in strategies) {
  a <- st[[paste(conditions[1], s)]]; r <- st[[paste(conditions[2], s)]]
  tt <- t.test(a$b, r$b)
  n1 <- length(a$b); n2 <- length(r$b)
  sp <- sqrt(((n1 - 1) * var(a$b) + (n2 - 1) * var(r$b)) / (n1 + n2 - 2))
  N <- n1 * n2 / (n1 + n2)
  lbf <- log_bf_point((mean(a$b) - mean(r$b)) / sp * sqrt(N), N, n1 + n2 - 2, sqrt(2) / 2)
  chk <- extractBF(ttestBF(a$b, r$b, rscale = sqrt(2) / 2), logbf = TRUE)$bf
  rows[[length(rows) + 1]] <- row("difference", s, paste0(conditions[1], "-", conditions[2]), tt, n1 + n2,
                                  a$left + r$left, lbf, chk)
}
write.csv(do.call(rbind, rows), "exposure_by_condition_golden.csv", row.names = FALSE, quote = FALSE)
