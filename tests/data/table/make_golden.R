# Regenerates golden_table1.csv: R's t.test / p.adjust for scores_small.csv, per mode, metric and
# iteration, the reference for tests/tables/test_table1.cpp.   Rscript make_golden.R
d <- read.csv("scores_small.csv", stringsAsFactors = FALSE)
refs <- c(error = 0.5, confusion = 0.95)
out <- list()
add <- function(mode, metric, it, group1, group2, tt) {
  out[[length(out) + 1]] <<- data.frame(
    mode = mode, metric = metric, iteration = it, group1 = group1, group2 = group2,
    statistic = unname(tt$statistic), df = unname(tt$parameter), p_value = tt$p.value,
    conf_low = tt$conf.int[1], conf_high = tt$conf.int[2], estimate = unname(tt$estimate[1]))
}
safe <- function(expr) tryCatch(expr, error = function(e) NULL)
for (m in names(refs)) {
  for (cond in c("adaptive", "random")) {
    for (it in 1:5) {
      x <- d[d$condition == cond & d$iteration == it, m]
      x <- x[!is.na(x)]
      tt <- safe(t.test(x, mu = refs[[m]]))
      if (!is.null(tt)) add("one_sample", m, it, cond, "", tt)
    }
  }
  for (it in 1:5) {
    a <- d[d$condition == "adaptive" & d$iteration == it, ]
    b <- d[d$condition == "random" & d$iteration == it, ]
    x <- a[[m]][!is.na(a[[m]])]; y <- b[[m]][!is.na(b[[m]])]
    add("welch", m, it, "adaptive", "random", t.test(x, y))
    add("student", m, it, "adaptive", "random", t.test(x, y, var.equal = TRUE))
    pa <- merge(a[, c("participant", m)], b[, c("participant", m)], by = "participant")
    pa <- pa[complete.cases(pa), ]
    add("paired", m, it, "adaptive", "random", t.test(pa[[2]], pa[[3]], paired = TRUE))
  }
}
g <- do.call(rbind, out)
# Holm within one metric column of one comparison (the Welch family).
g$p_holm <- NA
for (m in names(refs)) {
  i <- g$mode == "welch" & g$metric == m
  g$p_holm[i] <- p.adjust(g$p_value[i], "holm")
}
num <- sapply(g, is.numeric)
g[num] <- lapply(g[num], function(v) ifelse(is.na(v), "", sprintf("%.17g", v)))
write.csv(g, "golden_table1.csv", row.names = FALSE, quote = FALSE)

# golden_describe.csv: what `feint describe scores_small.csv --column error --by condition` must
# print (sd n-1, quantile type 7, t CI, lag-1 autocorrelation in file order as acf()).
rows <- list()
for (cond in c("adaptive", "random")) {
  x <- d$error[d$condition == cond]
  x <- x[!is.na(x)]
  n <- length(x); m <- mean(x); s <- sd(x); q <- quantile(x, c(0.25, 0.5, 0.75), type = 7)
  ci <- t.test(x)$conf.int
  r1 <- acf(x, lag.max = 1, plot = FALSE)$acf[2]
  rows[[length(rows) + 1]] <- data.frame(group = cond, n = n, mean = m, sd = s, se = s / sqrt(n),
    min = min(x), q1 = q[[1]], median = q[[2]], q3 = q[[3]], max = max(x),
    conf_low = ci[1], conf_high = ci[2], autocorr_lag1 = r1)
}
dd <- do.call(rbind, rows)
num <- sapply(dd, is.numeric)
dd[num] <- lapply(dd[num], function(v) sprintf("%.17g", v))
write.csv(dd, "golden_describe.csv", row.names = FALSE, quote = FALSE)
