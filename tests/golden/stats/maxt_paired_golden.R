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
# Drawn after the cases above, so that their draws stay as they were.
# 5. 11 x 5, unbalanced: pairs missing at random and by design (P03 has one pair only, column 4
#    has 6 pairs), two-sided.
a5 <- matrix(round(rnorm(55, 0.3, 1), 3), nrow = 11); b5 <- matrix(round(rnorm(55, 0, 1), 3), nrow = 11)
a5[3, -2] <- NA; b5[c(1, 5, 8, 9, 11), 4] <- NA; a5[cbind(c(2, 6, 10, 7), c(1, 3, 5, 5))] <- NA
cases[[5]] <- list(name = "paired_unbalanced_missing", a = a5, b = b5, alternative = "two.sided")
# 6. 12 x 6 with a participant effect on every difference (dependent iterations), a shift growing
#    over the iterations, 10 % of the pairs missing, one-sided (greater): 4096 sign vectors.
u <- rnorm(12, 0, 0.8)
a6 <- matrix(round(rep(u, 6) + rep(0.12 * (1:6), each = 12) + rnorm(72), 3), nrow = 12)
b6 <- matrix(round(rnorm(72), 3), nrow = 12)
a6[sample(72, 7)] <- NA
cases[[6]] <- list(name = "paired_greater_dependent", a = a6, b = b6, alternative = "greater")
# 7. 7 x 3 on a 0.5 grid: zero differences, tied statistics (columns 1 and 3 the same pairs), a
#    missing pair; two-sided.
a7 <- matrix(round(runif(21, 0, 4) * 2) / 2, nrow = 7); b7 <- matrix(round(runif(21, 0, 4) * 2) / 2, nrow = 7)
b7[c(2, 4), 1] <- a7[c(2, 4), 1]; b7[5, 2] <- a7[5, 2]
a7[, 3] <- a7[, 1]; b7[, 3] <- b7[, 1]; a7[6, 2] <- NA
cases[[7]] <- list(name = "paired_ties_zeros", a = a7, b = b7, alternative = "two.sided")

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
