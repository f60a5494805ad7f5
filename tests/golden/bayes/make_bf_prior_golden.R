# JZS Bayes factors of a small scores table at several prior scales r (the prior scale is
# settable, `--bf-prior-scale`). Regenerate from the repository root with R 4.2:
#   Rscript tests/golden/bayes/make_bf_prior_golden.R
# Writes prior_scale_scores.csv (participant, condition, iteration, error; 12 adaptive and 9 random
# participants, 3 iterations) and bf_prior_golden.csv: for every test feint table runs on it (each
# condition against 0.5, and adaptive against random), t, N, nu and the exact log BF10 at r =
# sqrt(2)/2 (medium), 1 (wide), sqrt(2) (ultrawide) and 0.5, from make_bf_golden.R's integral of
# the definition (integrate, rel.tol 1e-12; its functions are read from that file, not copied).
for (e in parse("tests/golden/bayes/make_bf_golden.R")) {
  if (is.call(e) && identical(e[[1]], as.name("<-")) && is.call(e[[3]]) &&
      identical(e[[3]][[1]], as.name("function"))) eval(e)
}
tol <- 1e-12
g17 <- function(x) sprintf("%.17g", x)
set.seed(20261126)
rows <- list()
for (cond in c("adaptive", "random")) {
  n <- if (cond == "adaptive") 12 else 9
  for (i in seq_len(n)) for (it in 1:3) {
    mu <- if (cond == "adaptive") 0.5 + 0.04 * it else 0.47
    rows[[length(rows) + 1]] <- data.frame(
      participant = sprintf("%s%02d", substr(cond, 1, 1), i), condition = cond, iteration = it,
      error = round(mu + rnorm(1, 0, 0.06), 6))
  }
}
d <- do.call(rbind, rows)
write.csv(d, "tests/golden/bayes/prior_scale_scores.csv", row.names = FALSE, quote = FALSE)
scales <- c(medium = sqrt(2) / 2, wide = 1, ultrawide = sqrt(2), half = 0.5)
out <- list()
add <- function(test, group1, group2, it, t, N, nu) {
  lb <- sapply(scales, function(r) log_bf_point(t, N, nu, r))
  out[[length(out) + 1]] <<- data.frame(test = test, group1 = group1, group2 = group2, iteration = it,
    t = g17(t), N = g17(N), nu = nu, log_bf_medium = g17(lb[1]), log_bf_wide = g17(lb[2]),
    log_bf_ultrawide = g17(lb[3]), log_bf_half = g17(lb[4]))
}
for (it in 1:3) {
  for (cond in c("adaptive", "random")) {
    x <- d$error[d$condition == cond & d$iteration == it]
    add("one_sample_t", cond, "", it, unname(t.test(x, mu = 0.5)$statistic), length(x), length(x) - 1)
  }
  x <- d$error[d$condition == "adaptive" & d$iteration == it]
  y <- d$error[d$condition == "random" & d$iteration == it]
  n1 <- length(x); n2 <- length(y)
  add("two_sample", "adaptive", "random", it, unname(t.test(x, y, var.equal = TRUE)$statistic),
      n1 * n2 / (n1 + n2), n1 + n2 - 2)
}
res <- do.call(rbind, out)
write.csv(res, "tests/golden/bayes/bf_prior_golden.csv", row.names = FALSE, quote = FALSE)
print(res)
