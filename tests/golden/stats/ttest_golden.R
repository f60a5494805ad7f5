# Golden values for feint's t-tests, TOST, effect sizes and p.adjust (tests/stats/test_ttest_golden.cpp).
# Regenerate from the repository root with R 4.2:
#   Rscript tests/golden/stats/ttest_golden.R tests/golden/stats
# Writes ttest_golden.csv and p_adjust_golden.csv. Numbers are printed with 17 significant digits
# (they read back as the same doubles); samples are ';'-separated within a field.
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) >= 1) args[1] else "tests/golden/stats"
set.seed(20240521)
g <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
vec <- function(x) paste(g(x), collapse = ";")

# Hedges' exact correction J(df) = Gamma(df/2) / (sqrt(df/2) Gamma((df-1)/2)); lgamma for large df.
J <- function(df) {
  if (df <= 1) return(NA_real_)
  if (df < 300) gamma(df / 2) / (sqrt(df / 2) * gamma((df - 1) / 2))
  else exp(lgamma(df / 2) - lgamma((df - 1) / 2)) / sqrt(df / 2)
}
pooled_sd <- function(x, y) {
  nx <- length(x); ny <- length(y)
  v <- 0
  if (nx > 1) v <- v + (nx - 1) * var(x)
  if (ny > 1) v <- v + (ny - 1) * var(y)
  sqrt(v / (nx + ny - 2))
}

# One case: kind is one_sample, welch, student, paired, tost_one_sample, tost_welch, tost_student,
# tost_paired. Effect sizes by formula: d = (mean - mu) / sd (one-sample), (mean(x) - mean(y) - mu) /
# pooled sd (two-sample, Welch too), d_z = (mean(x - y) - mu) / sd(x - y) (paired); g = d * J(df),
# df = n - 1 (one-sample, paired) or n1 + n2 - 2 (two-sample).
run_case <- function(kind, x, y, alternative, conf, mu, delta) {
  res <- list(computed = TRUE, statistic = NA, df = NA, p = NA, lo = NA, hi = NA, est = NA,
              d = NA, g = NA)
  effect <- function() {
    if (kind %in% c("one_sample", "tost_one_sample")) {
      d <- (mean(x) - mu) / sd(x); dfj <- length(x) - 1
    } else if (kind %in% c("paired", "tost_paired")) {
      z <- x - y; d <- (mean(z) - mu) / sd(z); dfj <- length(z) - 1
    } else {
      d <- (mean(x) - mean(y) - mu) / pooled_sd(x, y); dfj <- length(x) + length(y) - 2
    }
    c(d, d * J(dfj))
  }
  tt <- function(alt, m, cl) {
    switch(kind,
      one_sample = , tost_one_sample = t.test(x, mu = m, alternative = alt, conf.level = cl),
      welch = , tost_welch = t.test(x, y, mu = m, alternative = alt, conf.level = cl),
      student = , tost_student = t.test(x, y, mu = m, alternative = alt, conf.level = cl,
                                        var.equal = TRUE),
      paired = , tost_paired = t.test(x, y, mu = m, alternative = alt, conf.level = cl,
                                      paired = TRUE))
  }
  r <- tryCatch({
    if (startsWith(kind, "tost")) {
      lower <- tt("greater", mu - delta, conf)
      upper <- tt("less", mu + delta, conf)
      centre <- tt("two.sided", mu, 1 - 2 * (1 - conf))
      worse <- if (lower$p.value >= upper$p.value) lower else upper
      list(statistic = worse$statistic, df = worse$parameter, p = worse$p.value,
           lo = centre$conf.int[1], hi = centre$conf.int[2], est = centre$estimate)
    } else {
      t <- tt(alternative, mu, conf)
      list(statistic = t$statistic, df = t$parameter, p = t$p.value, lo = t$conf.int[1],
           hi = t$conf.int[2], est = t$estimate)
    }
  }, error = function(e) NULL)
  if (is.null(r) || !is.finite(r$statistic)) {
    res$computed <- FALSE
    return(res)
  }
  est <- if (length(r$est) == 2) r$est[1] - r$est[2] else r$est[1]
  e <- effect()
  list(computed = TRUE, statistic = r$statistic, df = r$df, p = r$p, lo = r$lo, hi = r$hi,
       est = est, d = e[1], g = e[2])
}

alts <- c("two.sided", "greater", "less")
confs <- c(0.95, 0.9, 0.99, 0.8, 0.999)
sizes <- c(2:12, 15, 20, 25, 30, 40, 50, 75, 100, 150, 200)
draw <- function(n, style, shift = 0) {
  switch(style,
    normal = rnorm(n, mean = 0.5 + shift, sd = runif(1, 0.05, 2)),
    wide = rnorm(n, mean = 100 + shift, sd = 30),
    likert = as.numeric(sample(1:7, n, replace = TRUE)) + shift,  # ties
    rounded = round(rnorm(n, 0.6 + shift, 0.15), 2),                 # ties
    skewed = rexp(n, rate = 3) + shift)
}
styles <- c("normal", "wide", "likert", "rounded", "skewed")
cases <- list()
add <- function(kind, x, y, alternative, conf, mu, delta = NA) {
  r <- run_case(kind, x, if (is.null(y)) numeric() else y, alternative, conf, mu, delta)
  cases[[length(cases) + 1]] <<- data.frame(
    id = length(cases) + 1, kind = kind, alternative = alternative, conf_level = g(conf),
    mu = g(mu), delta = g(delta), x = vec(x), y = if (is.null(y)) "" else vec(y),
    computed = r$computed, statistic = g(r$statistic), df = g(r$df), p_value = g(r$p),
    conf_low = g(r$lo), conf_high = g(r$hi), estimate = g(r$est), cohen_d = g(r$d),
    hedges_g = g(r$g))
}

i <- 0
for (kind in c("one_sample", "welch", "student", "paired")) {
  for (k in 1:55) {
    i <- i + 1
    n1 <- sample(sizes, 1)
    n2 <- if (kind == "paired") n1 else sample(sizes, 1)
    style <- styles[(k %% length(styles)) + 1]
    alt <- alts[(k %% 3) + 1]
    conf <- confs[(k %/% 3) %% length(confs) + 1]
    x <- draw(n1, style)
    if (kind == "one_sample") {
      mu <- mean(x) + sample(c(-1, 0, 0.3, 1), 1) * sd(x) * runif(1)
      add(kind, x, NULL, alt, conf, round(mu, 3))
    } else {
      y <- if (kind == "paired") x + rnorm(n1, runif(1, -0.3, 0.3), runif(1, 0.01, 0.5))
           else draw(n2, style, shift = sample(c(0, 0.1, 0.5), 1))
      if (kind == "welch" && k %% 4 == 0) y <- y * 5  # very unequal variances
      add(kind, x, y, alt, conf, sample(c(0, 0, 0.1, -0.2), 1))
    }
  }
}
# Tiny p-values, down to 1e-200 and below the smallest double (R reports 0 there).
for (shift in c(1, 2, 4, 6, 8, 10, 12, 16)) {
  x <- rnorm(200, shift, 1)
  add("one_sample", x, NULL, "two.sided", 0.95, 0)
  add("one_sample", x, NULL, "greater", 0.99, 0)
  add("welch", x, rnorm(150, 0, 2), "two.sided", 0.95, 0)
  add("student", x, rnorm(200, 0, 1), "greater", 0.9, 0)
  add("paired", x, rnorm(200, 0, 0.2), "two.sided", 0.95, 0)
}
add("welch", rnorm(200, 16, 1), rnorm(200, 0, 1), "less", 0.95, 0)  # p = 1 side
# Not computable: constant data (R: "data are essentially constant"), n < 2.
add("one_sample", rep(0.5, 10), NULL, "two.sided", 0.95, 0.5)
add("one_sample", rep(3, 4), NULL, "greater", 0.95, 1)
add("one_sample", c(0.7), NULL, "two.sided", 0.95, 0.5)
add("welch", rep(1, 5), rep(1, 7), "two.sided", 0.95, 0)
add("student", rep(2, 3), rep(2, 3), "two.sided", 0.95, 0)
add("welch", c(1, 2, 3), c(4), "two.sided", 0.95, 0)
add("paired", c(1, 2, 3), c(0, 1, 2), "two.sided", 0.95, 0)  # constant differences
# Student's test with a single value in one group (R allows it), and constant x against varying y.
add("student", c(5), c(1, 2, 4, 3), "two.sided", 0.95, 0)
add("welch", rep(1, 5), c(1, 2, 4, 3), "greater", 0.9, 0)
# TOST: one-sample, Welch, Student, paired; equivalent and not.
for (k in 1:10) {
  n <- sample(c(5, 10, 20, 40, 100), 1)
  conf <- c(0.95, 0.9, 0.975)[(k %% 3) + 1]
  x <- rnorm(n, 0.5, 0.1)
  delta <- c(0.02, 0.05, 0.1, 0.2)[(k %% 4) + 1]
  add("tost_one_sample", x, NULL, "two.sided", conf, 0.5, delta)
  y <- rnorm(sample(c(6, 12, 30), 1), 0.52, 0.15)
  add("tost_welch", x, y, "two.sided", conf, 0, delta)
  add("tost_student", x, y, "two.sided", conf, 0, delta)
  add("tost_paired", x, x + rnorm(n, 0.01, 0.05), "two.sided", conf, 0, delta)
}
tab <- do.call(rbind, cases)
write.csv(tab, file.path(out, "ttest_golden.csv"), row.names = FALSE, quote = FALSE)

# p.adjust: every method on vectors with ties, NA entries, n = 1 and n = 2 (hommel -> hochberg).
methods <- c("none", "bonferroni", "holm", "hochberg", "hommel", "BH", "BY")
pvecs <- list(c(0.01), c(NA), c(0.03, 0.2), c(0.04, NA, 0.01),
              c(0.01, 0.02, 0.03, 0.04, 0.05), c(0.01, 0.01, 0.02, 0.02, 0.5, 0.5, 1),
              c(1e-200, 1e-10, 0.003, NA, 0.049, 0.051, NA, 0.9),
              round(runif(20), 3), runif(20)^4, c(runif(12) / 50, NA, runif(7)),
              c(0.2, 0.2, 0.2, 0.2), sort(runif(9)), rev(sort(runif(9) / 10)))
rows <- list()
for (j in seq_along(pvecs)) for (m in methods) {
  rows[[length(rows) + 1]] <- data.frame(id = j, method = m, p = vec(pvecs[[j]]),
                                         adjusted = vec(p.adjust(pvecs[[j]], m)))
}
write.csv(do.call(rbind, rows), file.path(out, "p_adjust_golden.csv"), row.names = FALSE,
          quote = FALSE)
