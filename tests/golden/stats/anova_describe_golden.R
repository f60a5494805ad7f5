# Golden values for feint's one-way ANOVA, Welch ANOVA and describe() (tests/stats/test_anova_golden.cpp,
# tests/stats/test_descriptive.cpp). Regenerate from the repository root with R 4.2:
#   Rscript tests/golden/stats/anova_describe_golden.R tests/golden/stats
# Writes anova_golden.csv (groups '|'-separated, values ';'-separated) and describe_golden.csv.
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) >= 1) args[1] else "tests/golden/stats"
set.seed(7031)
g <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
vec <- function(x) paste(g(x), collapse = ";")

rows <- list()
for (case in 1:60) {
  k <- sample(2:6, 1)
  sizes <- sample(c(2:8, 10, 15, 25, 40), k, replace = TRUE)
  style <- case %% 3
  groups <- lapply(seq_len(k), function(j) {
    n <- sizes[j]
    if (style == 0) rnorm(n, mean = 0.5 + 0.1 * j * (case %% 2), sd = runif(1, 0.05, 1))
    else if (style == 1) as.numeric(sample(1:7, n, replace = TRUE))  # Likert: ties
    else round(rexp(n, 2) + 0.2 * j, 2)
  })
  y <- unlist(groups)
  f <- factor(rep(seq_len(k), sizes))
  a <- anova(lm(y ~ f))
  r2 <- summary(lm(y ~ f))$r.squared
  w <- tryCatch(oneway.test(y ~ f), error = function(e) NULL)
  wok <- !is.null(w) && is.finite(w$statistic)
  rows[[case]] <- data.frame(
    id = case, groups = paste(sapply(groups, vec), collapse = "|"),
    f = g(a[["F value"]][1]), df1 = g(a$Df[1]), df2 = g(a$Df[2]), p = g(a[["Pr(>F)"]][1]),
    ss_between = g(a[["Sum Sq"]][1]), ss_within = g(a[["Sum Sq"]][2]), r_squared = g(r2),
    welch_computed = wok, welch_f = g(if (wok) w$statistic else NA),
    welch_df1 = g(if (wok) w$parameter[1] else NA), welch_df2 = g(if (wok) w$parameter[2] else NA),
    welch_p = g(if (wok) w$p.value else NA))
}
write.csv(do.call(rbind, rows), file.path(out, "anova_golden.csv"), row.names = FALSE, quote = FALSE)

# describe(): quantile type 7, t-based CI of the mean (t.test's conf.int), lag-1 autocorrelation (acf).
rows <- list()
samples <- list(c(3), c(1, 2), c(5, 5, 5, 5), c(2, 7, 1, 8, 2, 8, 1, 8), 1:10 / 7)
for (n in c(3, 4, 5, 7, 12, 20, 33, 50, 101, 200)) {
  samples[[length(samples) + 1]] <- rnorm(n, 0.5, 0.2)
  samples[[length(samples) + 1]] <- as.numeric(sample(1:5, n, replace = TRUE))
}
confs <- c(0.95, 0.9, 0.99)
for (j in seq_along(samples)) {
  x <- samples[[j]]
  conf <- confs[(j %% 3) + 1]
  n <- length(x)
  q <- quantile(x, c(0.25, 0.5, 0.75), type = 7)
  ci <- if (n >= 2 && sd(x) > 0) t.test(x, conf.level = conf)$conf.int else c(NA, NA)
  ac <- if (n >= 2 && sd(x) > 0) acf(x, lag.max = 1, plot = FALSE)$acf[2] else NA
  rows[[j]] <- data.frame(id = j, x = vec(x), conf_level = g(conf), n = n, mean = g(mean(x)),
                          sd = g(if (n >= 2) sd(x) else NA),
                          se = g(if (n >= 2) sd(x) / sqrt(n) else NA), min = g(min(x)),
                          q1 = g(q[1]), median = g(q[2]), q3 = g(q[3]), max = g(max(x)),
                          conf_low = g(ci[1]), conf_high = g(ci[2]), autocorr_lag1 = g(ac))
}
write.csv(do.call(rbind, rows), file.path(out, "describe_golden.csv"), row.names = FALSE, quote = FALSE)
