# Golden values of the sign-flip step-down maxT adjustment of paired t tests
# (feint/stats/permutation.hpp, maxt_step_down_paired) by complete enumeration in R: every one of
# the 2^P sign vectors (each participant's conditions swapped or not, all iterations together),
# each column's statistic from t.test(paired = TRUE) on the signed pairs. Run from the root:
#   Rscript tests/golden/stats/maxt_paired_golden.R > tests/golden/stats/maxt_paired_golden.csv
# One row per case and column: the case's differences A - B (participant-major, ';' between
# values, NA = no pair), the options, and the expected t, p_raw, p_adjusted (NA: not computable).
options(digits = 17, warn = 1)

paired_t <- function(a, b) {
  tryCatch(unname(t.test(a, b, paired = TRUE)$statistic), error = function(e) NA_real_)
}
stat_of <- function(t, alternative) {
  if (is.na(t)) return(-Inf)
  switch(alternative, two.sided = abs(t), greater = t, less = -t)
}

# a, b: participants x columns (condition A, condition B); a participant's swap exchanges its rows.
maxt_paired <- function(a, b, alternative) {
  J <- ncol(a); P <- nrow(a)
  col_t <- function(s) sapply(seq_len(J), function(j) {
    ok <- !is.na(a[, j]) & !is.na(b[, j])
    x <- ifelse(s == 1, b[, j], a[, j]); y <- ifelse(s == 1, a[, j], b[, j])
    paired_t(x[ok], y[ok])
  })
  t_obs <- col_t(integer(P))
  obs <- sapply(t_obs, stat_of, alternative = alternative)
  ok <- which(is.finite(obs))
  ord <- ok[order(-obs[ok])]
  reach_max <- numeric(length(ord)); reach_own <- numeric(J)
  n <- 2^P
  for (b_ in 0:(n - 1)) {
    s <- as.integer(intToBits(b_))[1:P]
    st <- sapply(col_t(s), stat_of, alternative = alternative)
    u <- -Inf
    for (r in rev(seq_along(ord))) {
      j <- ord[r]
      u <- max(u, st[j])
      thr <- obs[j] - 1e-9 * max(1, abs(obs[j]))
      if (u >= thr) reach_max[r] <- reach_max[r] + 1
      if (st[j] >= thr) reach_own[j] <- reach_own[j] + 1
    }
  }
  p_adj <- rep(NA_real_, J); p_raw <- rep(NA_real_, J)
  p_adj[ord] <- cummax(reach_max / n)
  p_raw[ord] <- reach_own[ord] / n
  data.frame(column = seq_len(J) - 1, t = t_obs, p_raw = p_raw, p_adjusted = p_adj, labellings = n)
}

set.seed(20261127)
cases <- list()
# 1. 9 participants x 4 iterations, skewed (exponential) values, condition A higher at iteration 2.
a <- matrix(round(rexp(36), 4), nrow = 9); b <- matrix(round(rexp(36), 4), nrow = 9)
a[, 2] <- a[, 2] + 0.8
cases[[1]] <- list(name = "paired_two_sided", a = a, b = b, alternative = "two.sided")
# 2. The same data, one-sided (A greater).
cases[[2]] <- list(name = "paired_greater", a = a, b = b, alternative = "greater")
# 3. 10 x 3 with missing pairs (a participant who missed a trial), one-sided (less), correlated
#    conditions (a participant effect).
p <- rnorm(10, 0, 2)
a3 <- matrix(round(rep(p, 3) + rnorm(30), 3), nrow = 10); b3 <- matrix(round(rep(p, 3) + rnorm(30), 3), nrow = 10)
b3[, 3] <- b3[, 3] + 1.1
a3[2, 1] <- NA; b3[7, 1] <- NA; a3[5, 2] <- NA
cases[[3]] <- list(name = "paired_less_missing", a = a3, b = b3, alternative = "less")
# 4. A column with one pair only and a column with constant differences: both left out.
a4 <- matrix(round(runif(24), 3), nrow = 8); b4 <- matrix(round(runif(24), 3), nrow = 8)
a4[2:8, 2] <- NA
b4[, 3] <- a4[, 3] - 0.25
cases[[4]] <- list(name = "paired_untestable_columns", a = a4, b = b4, alternative = "two.sided")

cat("case,participants,columns,alternative,differences,column,t,p_raw,p_adjusted,labellings\n")
for (cs in cases) {
  r <- maxt_paired(cs$a, cs$b, cs$alternative)
  d <- cs$a - cs$b
  vals <- paste(ifelse(is.na(t(d)), "NA", format(t(d), digits = 17, trim = TRUE)), collapse = ";")
  for (i in seq_len(nrow(r))) {
    cat(sprintf("%s,%d,%d,%s,%s,%d,%s,%s,%s,%d\n", cs$name, nrow(d), ncol(d), cs$alternative, vals,
                r$column[i], format(r$t[i], digits = 17), format(r$p_raw[i], digits = 17),
                format(r$p_adjusted[i], digits = 17), r$labellings[i]))
  }
}
