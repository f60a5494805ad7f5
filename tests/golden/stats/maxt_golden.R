# Golden values of the Westfall-Young step-down maxT adjustment (feint/stats/permutation.hpp) by
# complete enumeration in R: every labelling of the participants with the observed group sizes,
# each column's statistic from t.test() itself. Run from the repository root:
#   Rscript tests/golden/stats/maxt_golden.R > tests/golden/stats/maxt_golden.csv
# One row per case and column: the case's data (participant-major, ';' between values, NA =
# missing), the groups, the options, and the expected t, p_raw, p_adjusted (NA: not computable).
options(digits = 17, warn = 1)

stat_of <- function(x, y, var_equal, alternative) {
  t <- tryCatch(unname(t.test(x, y, var.equal = var_equal)$statistic), error = function(e) NA_real_)
  if (is.na(t)) return(-Inf)
  switch(alternative, two.sided = abs(t), greater = t, less = -t)
}

maxt <- function(values, group, var_equal, alternative) {
  J <- ncol(values)
  col_stats <- function(g) sapply(seq_len(J), function(j) {
    v <- values[, j]
    stat_of(v[g == 1 & !is.na(v)], v[g == 0 & !is.na(v)], var_equal, alternative)
  })
  col_t <- sapply(seq_len(J), function(j) {
    v <- values[, j]
    tryCatch(unname(t.test(v[group == 1 & !is.na(v)], v[group == 0 & !is.na(v)],
                           var.equal = var_equal)$statistic), error = function(e) NA_real_)
  })
  obs <- col_stats(group)
  ok <- which(is.finite(obs))
  ord <- ok[order(-obs[ok])]
  P <- nrow(values); k <- sum(group)
  sets <- combn(P, k)
  reach_max <- numeric(length(ord)); reach_own <- numeric(J)
  for (b in seq_len(ncol(sets))) {
    g <- integer(P); g[sets[, b]] <- 1L
    s <- col_stats(g)
    u <- -Inf
    for (r in rev(seq_along(ord))) {
      j <- ord[r]
      u <- max(u, s[j])
      thr <- obs[j] - 1e-9 * max(1, abs(obs[j]))
      if (u >= thr) reach_max[r] <- reach_max[r] + 1
      if (s[j] >= thr) reach_own[j] <- reach_own[j] + 1
    }
  }
  n <- ncol(sets)
  p_adj <- rep(NA_real_, J); p_raw <- rep(NA_real_, J)
  p_adj[ord] <- cummax(reach_max / n)
  p_raw[ord] <- reach_own[ord] / n
  data.frame(column = seq_len(J) - 1, t = col_t, p_raw = p_raw, p_adjusted = p_adj, labellings = n)
}

set.seed(20261126)
cases <- list()
# 1. 5 + 5 participants x 3 iterations, skewed (exponential) values, a shift in column 3.
v <- matrix(round(rexp(30), 4), nrow = 10)
v[1:5, 3] <- v[1:5, 3] + 1.5
cases[[1]] <- list(name = "welch_two_sided", values = v, group = c(rep(1, 5), rep(0, 5)),
                   var_equal = FALSE, alternative = "two.sided")
# 2. The same data, Student's t, one-sided (group 1 greater).
cases[[2]] <- list(name = "student_greater", values = v, group = c(rep(1, 5), rep(0, 5)),
                   var_equal = TRUE, alternative = "greater")
# 3. 6 + 6 x 4 with missing values, groups interleaved, Welch, one-sided (less).
w <- matrix(round(rnorm(48, 10, 2), 3), nrow = 12)
w[c(2, 7), 1] <- NA; w[5, 4] <- NA
w[c(1, 3, 5, 7, 9, 11), 2] <- w[c(1, 3, 5, 7, 9, 11), 2] - 3
cases[[3]] <- list(name = "welch_less_missing", values = w, group = rep(c(1, 0), 6),
                   var_equal = FALSE, alternative = "less")
# 4. A column that cannot be tested (one value in group 0) and a constant column: both left out.
z <- matrix(round(runif(28, 0, 1), 3), nrow = 7)
z[c(5, 6), 2] <- NA
z[, 3] <- 0.25
cases[[4]] <- list(name = "welch_untestable_columns", values = z, group = c(1, 1, 1, 1, 0, 0, 0),
                   var_equal = FALSE, alternative = "two.sided")

cat("case,participants,columns,group,var_equal,alternative,values,column,t,p_raw,p_adjusted,labellings\n")
for (cs in cases) {
  r <- maxt(cs$values, cs$group, cs$var_equal, cs$alternative)
  vals <- paste(ifelse(is.na(t(cs$values)), "NA", format(t(cs$values), digits = 17, trim = TRUE)), collapse = ";")
  for (i in seq_len(nrow(r))) {
    cat(sprintf("%s,%d,%d,%s,%s,%s,%s,%d,%s,%s,%s,%d\n", cs$name, nrow(cs$values), ncol(cs$values),
                paste(cs$group, collapse = ";"), tolower(cs$var_equal), cs$alternative, vals,
                r$column[i], format(r$t[i], digits = 17), format(r$p_raw[i], digits = 17),
                format(r$p_adjusted[i], digits = 17), r$labellings[i]))
  }
}
