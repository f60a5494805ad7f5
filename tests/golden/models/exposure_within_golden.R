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

# ---- more data sets (drawn after the one above, each from its own seed, so that its draws and
# exposure_within.csv / exposure_within_golden.csv stay as they were) ------------------------------
# Written to exposure_within_sets.csv (set, participant, condition, iteration, strategy, error) and
# exposure_within_sets_golden.csv (set, the columns above, d_z and its 95 % interval: the exact
# roots of P(T <= t; n - 1, ncp) = 0.975 / 0.025 by uniroot(tol = 1e-15), divided by sqrt(n)).
#  balanced      10 participants, 2 conditions, 9 iterations each, strategies in turn, complete;
#  unbalanced    16 participants, blocks of 6 to 14 iterations (different per condition), strategies
#                drawn with unequal probabilities, 15 % of the errors missing, 10 % of the trials
#                never recorded (absent rows), two participants in one condition only;
#  three         12 participants, 3 conditions within (slopes in each, the difference of the first
#                two), 8 % missing;
#  small_strong  5 participants, a strong slope difference, one missing error;
#  sparse        8 participants, 40 % of the errors missing and 20 % of the trials absent: many
#                participants without a slope, a strategy with fewer than 2 pairs (not computable,
#                NA in the golden).
# The noncentral t distribution function as the integral of its definition over the chi-squared
# variable: R's pt(ncp = ) switches to a rough approximation above ncp = 37.62.
pnt <- function(t, df, ncp)
  integrate(function(u) pnorm(t * sqrt(u / df) - ncp) * dchisq(u, df), 0, Inf, rel.tol = 1e-13,
            abs.tol = 0, subdivisions = 2000L)$value
d_interval <- function(t, n) {
  h <- function(x, p) pnt(t, n - 1, x) - p
  root <- function(p) {  # the smallest bracket that holds the root
    w <- 1
    while (h(t - w, p) * h(t + w, p) > 0) w <- 2 * w
    uniroot(h, c(t - w, t + w), p = p, tol = 1e-15)$root
  }
  c(root(0.975), root(0.025)) / sqrt(n)
}
gen_set <- function(name, seed, n, conds, len, probs, slope_true, missing, absent = 0, only_one = character(0),
                    rotate = FALSE) {
  set.seed(seed)
  rows <- list()
  for (i in seq_len(n)) for (cc in seq_along(conds)) {
    p <- sprintf("P%02d", i); k <- len(i, cc)
    s <- if (rotate) strategies[(seq_len(k) + i + cc) %% 3 + 1] else sample(strategies, k, TRUE, probs)
    rows[[length(rows) + 1]] <- data.frame(set = name, participant = p, condition = conds[cc],
                                           iteration = seq_len(k), strategy = s, cc = cc)
  }
  x <- do.call(rbind, rows)
  if (absent > 0) x <- x[-sample(nrow(x), round(absent * nrow(x))), ]
  for (p in only_one) x <- x[x$participant != p | x$cc == 1, ]
  x$exposure <- ave(seq_len(nrow(x)), x$participant, x$condition, x$strategy, FUN = seq_along) - 1
  x$error <- 0.45 + 0.02 * (x$cc - 1) + slope_true[cbind(x$cc, match(x$strategy, strategies))] * x$exposure + rnorm(nrow(x), 0, 0.08)
  if (missing > 0) x$error[sample(nrow(x), round(missing * nrow(x)))] <- NA
  x
}
sl <- function(...) matrix(c(...), ncol = 3, byrow = TRUE, dimnames = list(NULL, strategies))
sets <- list(
  list("balanced", 101, 10, c("adaptive", "random"), function(i, c) 9, NULL,
       sl(-0.01, -0.03, 0, 0, -0.01, 0.01), 0, 0, character(0), TRUE),
  list("unbalanced", 102, 16, c("adaptive", "random"), function(i, c) sample(6:14, 1), c(0.5, 0.3, 0.2),
       sl(-0.02, -0.01, 0.01, 0, -0.02, 0), 0.15, 0.10, c("P04", "P11")),
  list("three", 103, 12, c("adaptive", "random", "fixed"), function(i, c) 10, NULL,
       sl(-0.02, -0.03, 0, 0, -0.01, 0.01, -0.01, 0, 0.02), 0.08),
  list("small_strong", 104, 5, c("adaptive", "random"), function(i, c) 12, NULL,
       sl(-0.05, -0.06, -0.04, 0.01, 0.02, 0.01), 1 / 120),
  list("sparse", 105, 8, c("adaptive", "random"), function(i, c) 7, c(0.6, 0.3, 0.1),
       sl(-0.02, -0.02, -0.02, 0, 0, 0), 0.40, 0.20))
all_data <- list(); out <- list()
for (a in sets) {
  x <- gen_set(a[[1]], a[[2]], a[[3]], a[[4]], a[[5]], a[[6]], a[[7]], a[[8]],
               if (length(a) >= 9) a[[9]] else 0, if (length(a) >= 10) a[[10]] else character(0),
               if (length(a) >= 11) a[[11]] else FALSE)
  all_data[[length(all_data) + 1]] <- x
  d <- x  # stage1() reads d
  conds <- a[[4]]
  put <- function(kind, s, cond, tt, n, left, lbf = NA, chk = NA, dz = c(NA, NA, NA)) {
    r <- if (is.null(tt)) data.frame(kind = kind, strategy = s, condition = cond, n = n, left_out = left,
                                     estimate = "NA", se = "NA", df = "NA", t = "NA", p = "NA", lower = "NA",
                                     upper = "NA", log_bf10 = "NA", ttestbf_log_bf = "NA")
         else row(kind, s, cond, tt, n, left, lbf, chk)
    out[[length(out) + 1]] <<- cbind(data.frame(set = a[[1]]), r, d_z = g17(dz[1]), d_z_low = g17(dz[2]),
                                     d_z_high = g17(dz[3]))
  }
  st <- list()
  for (cond in conds) for (s in strategies) {
    st[[paste(cond, s)]] <- r <- stage1(cond, s)
    put("slope", s, cond, if (length(r$b) >= 2) t.test(r$b) else NULL, length(r$b), r$left)
  }
  for (s in strategies) {
    ra <- st[[paste(conds[1], s)]]; rb <- st[[paste(conds[2], s)]]
    both <- intersect(ra$who, rb$who)
    xa <- ra$b[match(both, ra$who)]; xb <- rb$b[match(both, rb$who)]
    n <- length(both)
    left <- length(ra$b) + length(rb$b) - 2 * n + ra$left + rb$left
    cname <- paste0(conds[1], "-", conds[2])
    if (n < 2) { put("difference", s, cname, NULL, n, left); next }
    tt <- t.test(xa, xb, paired = TRUE)
    tv <- tt$statistic[[1]]
    lbf <- log_bf_point(tv, n, n - 1, sqrt(2) / 2)
    chk <- extractBF(ttestBF(xa, xb, paired = TRUE, rscale = sqrt(2) / 2), logbf = TRUE)$bf
    dz <- c(mean(xa - xb) / sd(xa - xb), d_interval(tv, n))
    put("difference", s, cname, tt, n, left, lbf, chk, dz)
  }
}
dd <- do.call(rbind, all_data)
write.csv(dd[, c("set", "participant", "condition", "iteration", "strategy", "error")],
          "exposure_within_sets.csv", row.names = FALSE, quote = FALSE, na = "")
write.csv(do.call(rbind, out), "exposure_within_sets_golden.csv", row.names = FALSE, quote = FALSE)
