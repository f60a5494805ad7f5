# Golden exposure slopes within participants (tests/models/test_exposure_by_condition.cpp,
# ExposureByCondition.WithinParticipantsPairedDifferenceMatchesTTestPaired), by the two-stage method
# of models::exposure_slopes_by_condition with paired = true. Regenerate from tests/golden/models:
#   Rscript exposure_within_golden.R
# Data (written here, exposure_within.csv): 14 participants, each in both conditions (a block of 12
# iterations each), strategies drawn per trial, 8 % of the errors missing, one participant who never
# sees "ambiguous" twice in one condition (left out of that strategy), one who has no trial of
# condition "random" with "switching" at 2 distinct exposures.
#  exposure: the participant's earlier trials of the same strategy in the same condition;
#  stage 1: coef(lm(error ~ exposure)) per participant x condition x strategy (>= 2 finite trials at
#    >= 2 distinct exposures);
#  stage 2: per condition and strategy t.test(slopes); the difference adaptive - random per strategy
#    = t.test(a, b, paired = TRUE) over the participants with a slope in both conditions, with the
#    JZS Bayes factor of the one-sample form (t, n, n - 1) by log_bf_point() of
#    tests/golden/bayes/make_bf_golden.R; ttestBF(a, b, paired = TRUE) is a cross-check column.
suppressMessages(library(BayesFactor))
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
tol <- 1e-12
for (e in parse("../bayes/make_bf_golden.R"))
  if (is.call(e) && identical(e[[1]], as.name("<-")) && identical(e[[2]], as.name("log_bf_point"))) eval(e)
stopifnot(exists("log_bf_point"))

set.seed(29)
strategies <- c("ambiguous", "exaggerating", "switching")
rows <- list()
for (p in sprintf("P%02d", 1:14)) for (cond in c("adaptive", "random")) {
  s <- sample(strategies, 12, replace = TRUE)
  if (p == "P03") s[s == "ambiguous"] <- "exaggerating"
  if (p == "P05" && cond == "random") s[s == "switching"] <- "ambiguous"
  rows[[length(rows) + 1]] <- data.frame(participant = p, condition = cond, iteration = 1:12, strategy = s)
}
d <- do.call(rbind, rows)
if (!any(d$participant == "P03" & d$strategy == "ambiguous")) d$strategy[d$participant == "P03" & d$iteration == 1 & d$condition == "adaptive"] <- "ambiguous"
d$exposure <- ave(seq_len(nrow(d)), d$participant, d$condition, d$strategy, FUN = seq_along) - 1
slope_true <- c(ambiguous = -0.01, exaggerating = -0.03, switching = 0)
d$error <- 0.45 + ifelse(d$condition == "adaptive", 0.02, 0) +
  slope_true[d$strategy] * d$exposure * ifelse(d$condition == "adaptive", 1.5, 1) + rnorm(nrow(d), 0, 0.08)
d$error[sample(nrow(d), round(0.08 * nrow(d)))] <- NA
write.csv(d[, c("participant", "condition", "iteration", "strategy", "error")], "exposure_within.csv",
          row.names = FALSE, quote = FALSE, na = "")

stage1 <- function(cond, s) {
  dc <- d[d$condition == cond & d$strategy == s & is.finite(d$error), ]
  b <- c(); who <- c(); left <- 0
  for (p in sort(unique(d$participant[d$condition == cond & d$strategy == s]))) {
    dp <- dc[dc$participant == p, ]
    if (nrow(dp) >= 2 && length(unique(dp$exposure)) >= 2) {
      b <- c(b, coef(lm(error ~ exposure, dp))[["exposure"]]); who <- c(who, p)
    } else left <- left + 1
  }
  list(b = b, who = who, left = left)
}
row <- function(kind, s, cond, tt, n, left, lbf = NA, chk = NA)
  data.frame(kind = kind, strategy = s, condition = cond, n = n, left_out = left,
             estimate = g17(tt$estimate[[1]]), se = g17(tt$stderr), df = g17(tt$parameter[[1]]),
             t = g17(tt$statistic[[1]]), p = g17(tt$p.value), lower = g17(tt$conf.int[1]),
             upper = g17(tt$conf.int[2]), log_bf10 = g17(lbf), ttestbf_log_bf = g17(chk))
st <- list(); out <- list()
for (cond in c("adaptive", "random")) for (s in strategies) {
  st[[paste(cond, s)]] <- r <- stage1(cond, s)
  out[[length(out) + 1]] <- row("slope", s, cond, t.test(r$b), length(r$b), r$left)
}
for (s in strategies) {
  a <- st[[paste("adaptive", s)]]; r <- st[[paste("random", s)]]
  both <- intersect(a$who, r$who)
  x <- a$b[match(both, a$who)]; y <- r$b[match(both, r$who)]
  tt <- t.test(x, y, paired = TRUE)
  n <- length(both)
  lbf <- log_bf_point(tt$statistic[[1]], n, n - 1, sqrt(2) / 2)
  chk <- extractBF(ttestBF(x, y, paired = TRUE, rscale = sqrt(2) / 2), logbf = TRUE)$bf
  left <- length(a$b) + length(r$b) - 2 * n + a$left + r$left
  out[[length(out) + 1]] <- row("difference", s, "adaptive-random", tt, n, left, lbf, chk)
}
write.csv(do.call(rbind, out), "exposure_within_golden.csv", row.names = FALSE, quote = FALSE)
