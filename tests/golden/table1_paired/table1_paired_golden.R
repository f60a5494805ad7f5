# Golden values of Table 1 with two conditions within participants (feint table --compare A,B
# --paired; tests/tables/test_table1_paired.cpp): per data set, metric and iteration, the paired t
# test of the participants measured in both conditions, its d_z and Hedges' g_z with their 95 %
# intervals, the JZS Bayes factor of the one-sample form and the Holm adjustment over the
# iterations of a metric. R 4.2 with BayesFactor. Run from the repository root:
#   Rscript tests/golden/table1_paired/table1_paired_golden.R
# Writes, into tests/golden/table1_paired/, the scores files (participant, condition, iteration,
# error, confusion; an empty cell = missing) and table1_paired_golden.csv (dataset, metric,
# iteration, quantity, value; %.17g, NA = none):
#   p2_complete.csv    12 participants, 5 iterations, complete
#   p2_missing.csv     14 participants, 6 iterations, empty cells and trials never recorded
#   p2_unbalanced.csv  15 participants: 3 in 'adaptive' only, 2 in 'random' only, empty cells
#   p2_small.csv       4 participants, 3 iterations: one pair at iteration 2 and constant
#                      differences of confusion at iteration 3 (not computable: NA)
#   p2_strong.csv      10 participants, 4 iterations, conditions far apart (p to 1e-9, an upper
#                      bound of d_z at ncp 37.7)
#   p2_ties.csv        9 participants, 5 iterations, values on a 0.1 grid (zero differences), empty cells
# Per cell: t.test(a, b, paired = TRUE) on the pairs matched by participant (t, df, p, the 95 %
# interval, the mean difference), n the pairs; d_z = mean(a - b) / sd(a - b) with the exact roots
# of P(T <= t; n - 1, ncp) = 0.975 / 0.025 (uniroot, tol 1e-15; the distribution function by pnt()
# below) over sqrt(n); g_z = d_z J(n - 1),
# J(m) = gamma(m / 2) / (sqrt(m / 2) gamma((m - 1) / 2)), its bounds those of d_z times J; the log
# BF10 by log_bf_point() of tests/golden/bayes/make_bf_golden.R (the defining integral, rel.tol
# 1e-12; r = sqrt(2) / 2), with BayesFactor's ttestBF(paired = TRUE) as a cross-check column
# (log_bf_ttestbf, not compared); p_holm: p.adjust(p, "holm") over the metric's iterations.
options(warn = 1)
suppressMessages(library(BayesFactor))
dir <- "tests/golden/table1_paired"
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
tol <- 1e-12
for (e in parse("tests/golden/bayes/make_bf_golden.R"))
  if (is.call(e) && identical(e[[1]], as.name("<-")) && identical(e[[2]], as.name("log_bf_point"))) eval(e)
stopifnot(exists("log_bf_point"))

# n participants, each in both conditions at every iteration; `shift` the difference adaptive -
# random (per iteration), `grid` the rounding of the values.
within_two <- function(n, iterations, shift, sd = 0.08, grid = 1e-4) {
  rows <- list()
  for (p in seq_len(n)) {
    person <- rnorm(1, 0, 0.06)
    for (cond in c("adaptive", "random")) for (it in seq_len(iterations)) {
      s <- if (cond == "adaptive") shift[it] else 0
      rows[[length(rows) + 1]] <- data.frame(
        participant = sprintf("P%02d", p), condition = cond, iteration = it,
        error = round((0.5 + person + s + rnorm(1, 0, sd)) / grid) * grid,
        confusion = round((0.85 - person - s + rnorm(1, 0, 1.5 * sd)) / grid) * grid)
    }
  }
  do.call(rbind, rows)
}
write_scores <- function(d, name) write.csv(d, file.path(dir, name), row.names = FALSE, quote = FALSE, na = "")

set.seed(20261128)
write_scores(within_two(12, 5, c(0, 0.02, 0.04, 0.06, 0.08)), "p2_complete.csv")
d <- within_two(14, 6, rep(0.03, 6))
d$error[sample(nrow(d), 9)] <- NA
d$confusion[sample(nrow(d), 7)] <- NA
d <- d[-sample(nrow(d), 6), ]  # trials never recorded
write_scores(d, "p2_missing.csv")
d <- within_two(15, 4, c(0.05, 0.03, 0.01, 0))
d <- d[!(d$participant %in% c("P02", "P07", "P13") & d$condition == "random"), ]
d <- d[!(d$participant %in% c("P05", "P10") & d$condition == "adaptive"), ]
d$error[sample(nrow(d), 4)] <- NA
d$confusion[sample(nrow(d), 3)] <- NA
write_scores(d, "p2_unbalanced.csv")
d <- within_two(4, 3, c(0.05, 0.05, 0.05))
d$error[d$iteration == 2 & d$condition == "random" & d$participant != "P01"] <- NA
i3 <- d$iteration == 3
d$confusion[i3 & d$condition == "random"] <- d$confusion[i3 & d$condition == "adaptive"] - 0.125
write_scores(d, "p2_small.csv")
write_scores(within_two(10, 4, c(0.15, 0.2, 0.25, 0.3), sd = 0.04), "p2_strong.csv")
d <- within_two(9, 5, rep(0.05, 5), sd = 0.1, grid = 0.1)
d$error[sample(nrow(d), 3)] <- NA
d$confusion[sample(nrow(d), 2)] <- NA
write_scores(d, "p2_ties.csv")
sets <- c("p2_complete.csv", "p2_missing.csv", "p2_unbalanced.csv", "p2_small.csv", "p2_strong.csv", "p2_ties.csv")

# ---- the statistics ------------------------------------------------------------------------------
# The noncentral t distribution function as the integral of its definition over the chi-squared
# variable: R's pt(ncp = ) switches to a rough approximation above ncp = 37.62 (off by 4e-3 there).
pnt <- function(t, df, ncp)
  integrate(function(u) pnorm(t * sqrt(u / df) - ncp) * dchisq(u, df), 0, Inf, rel.tol = 1e-13,
            abs.tol = 0, subdivisions = 2000L)$value
d_root <- function(t, df, p) {
  h <- function(x) pnt(t, df, x) - p
  w <- 1
  while (h(t - w) * h(t + w) > 0) w <- 2 * w  # the smallest bracket: pt is inexact at a large ncp
  uniroot(h, c(t - w, t + w), tol = 1e-15)$root
}
hedges_j <- function(m) exp(lgamma(m / 2) - log(sqrt(m / 2)) - lgamma((m - 1) / 2))

out <- list()
put <- function(ds, metric, it, quantity, value)
  out[[length(out) + 1]] <<- data.frame(dataset = ds, metric = metric, iteration = it, quantity = quantity,
                                        value = g17(unname(value)))
for (name in sets) {
  d <- read.csv(file.path(dir, name), na.strings = "", stringsAsFactors = FALSE)
  for (metric in c("error", "confusion")) {
    ps <- c()
    for (it in sort(unique(d$iteration))) {
      a <- d[d$condition == "adaptive" & d$iteration == it & !is.na(d[[metric]]), c("participant", metric)]
      b <- d[d$condition == "random" & d$iteration == it & !is.na(d[[metric]]), c("participant", metric)]
      m <- merge(a, b, by = "participant")
      x <- m[[2]]; y <- m[[3]]; n <- length(x)
      put(name, metric, it, "n", n)
      tt <- tryCatch(t.test(x, y, paired = TRUE), error = function(e) NULL)
      if (is.null(tt)) {
        for (q in c("t", "df", "p", "conf_low", "conf_high", "estimate", "d_z", "d_z_low", "d_z_high",
                    "g_z", "g_z_low", "g_z_high", "log_bf10", "log_bf_ttestbf")) put(name, metric, it, q, NA)
        ps <- c(ps, NA)
        next
      }
      t <- tt$statistic[[1]]
      put(name, metric, it, "t", t); put(name, metric, it, "df", tt$parameter[[1]])
      put(name, metric, it, "p", tt$p.value)
      put(name, metric, it, "conf_low", tt$conf.int[1]); put(name, metric, it, "conf_high", tt$conf.int[2])
      put(name, metric, it, "estimate", tt$estimate[[1]])
      dz <- mean(x - y) / sd(x - y); lo <- d_root(t, n - 1, 0.975) / sqrt(n); hi <- d_root(t, n - 1, 0.025) / sqrt(n)
      j <- hedges_j(n - 1)
      put(name, metric, it, "d_z", dz); put(name, metric, it, "d_z_low", lo); put(name, metric, it, "d_z_high", hi)
      put(name, metric, it, "g_z", dz * j); put(name, metric, it, "g_z_low", lo * j); put(name, metric, it, "g_z_high", hi * j)
      put(name, metric, it, "log_bf10", log_bf_point(t, n, n - 1, sqrt(2) / 2))
      put(name, metric, it, "log_bf_ttestbf",
          extractBF(ttestBF(x, y, paired = TRUE, rscale = sqrt(2) / 2), logbf = TRUE)$bf)
      ps <- c(ps, tt$p.value)
    }
    ok <- !is.na(ps)
    holm <- rep(NA, length(ps)); holm[ok] <- p.adjust(ps[ok], "holm")
    its <- sort(unique(d$iteration))
    for (k in seq_along(its)) put(name, metric, its[k], "p_holm", holm[k])
  }
}
write.csv(do.call(rbind, out), file.path(dir, "table1_paired_golden.csv"), row.names = FALSE, quote = FALSE)
