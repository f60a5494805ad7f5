# Golden values of the observer's conditions compared on the participants' fits
# (models::compare_conditions; tests/models/test_observer_compare.cpp): per data set, log beta and
# tau of condition A against B by Welch's t test (with Cohen's d of the pooled sd, Hedges' g, their
# 95 % intervals and the two-sample JZS Bayes factor) and by the Mann-Whitney test (with the
# rank-biserial correlation and its interval). R 4.2 with effectsize 0.8 and BayesFactor.
#   cd tests/golden/models && Rscript observer_compare_golden.R
# Writes observer_compare_data.csv (dataset, participant, condition, beta, tau, beta_at_bound,
# tau_at_bound: 1 = the estimate lies on the range's bound, beta at its maximum, tau at 0) and
# observer_compare_golden.csv (dataset, parameter, quantity, value; %.17g, NA = none):
#   balanced     8 + 8 participants
#   unbalanced   5 + 11 participants, unequal spreads
#   bounds       9 + 7: a beta of 0 (no log: left out of log beta), betas at the maximum, taus at 0
#   ties         10 + 9, betas and taus on a coarse grid (ties: the normal approximation of W)
#   small        2 + 3, and a third condition that is not compared
#   strong       30 + 25, conditions far apart (p far below 1e-6)
# Welch: t.test(x, y) (estimate = mean(x) - mean(y)); d = (mean(x) - mean(y)) / sd_pooled, its bounds
# the exact roots of P(T <= t_pooled; n1 + n2 - 2, ncp) = 0.975 / 0.025 (uniroot tol 1e-15, the
# distribution function integrated from its definition: R's pt(ncp = ) is rough above ncp 37.62)
# times sqrt(1 / n1 + 1 / n2); g = d J(n1 + n2 - 2) and its bounds those of d times J; the log BF10
# of the pooled t (N = n1 n2 / (n1 + n2), nu = n1 + n2 - 2, r = sqrt(2) / 2) by log_bf_point() of
# tests/golden/bayes/make_bf_golden.R, ttestBF(x, y) a cross-check column (log_bf_ttestbf, not
# compared). Mann-Whitney: wilcox.test(x, y) (exact without ties and n < 50, else the normal
# approximation with continuity correction), effectsize::rank_biserial(x, y).
options(warn = 1)
suppressMessages({ library(BayesFactor); library(effectsize) })
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
tol <- 1e-12
for (e in parse("../bayes/make_bf_golden.R"))
  if (is.call(e) && identical(e[[1]], as.name("<-")) && identical(e[[2]], as.name("log_bf_point"))) eval(e)
stopifnot(exists("log_bf_point"))
pnt <- function(t, df, ncp)
  integrate(function(u) pnorm(t * sqrt(u / df) - ncp) * dchisq(u, df), 0, Inf, rel.tol = 1e-13,
            abs.tol = 0, subdivisions = 2000L)$value
ncp_root <- function(t, df, p) {
  h <- function(x) pnt(t, df, x) - p
  w <- 1
  while (h(t - w) * h(t + w) > 0) w <- 2 * w
  uniroot(h, c(t - w, t + w), tol = 1e-15)$root
}
hedges_j <- function(m) exp(lgamma(m / 2) - log(sqrt(m / 2)) - lgamma((m - 1) / 2))

set.seed(20261129)
fits <- function(name, cond, n, log_beta_mean, log_beta_sd, tau_mean, tau_sd, first = 1, grid = 0) {
  beta <- exp(rnorm(n, log_beta_mean, log_beta_sd)); tau <- pmax(0, rnorm(n, tau_mean, tau_sd))
  if (grid > 0) { beta <- pmax(grid, round(beta / grid) * grid); tau <- round(tau / grid) * grid }
  data.frame(dataset = name, participant = sprintf("%s%02d", substr(cond, 1, 1), first - 1 + seq_len(n)),
             condition = cond, beta = signif(beta, 12), tau = signif(tau, 12), beta_at_bound = 0,
             tau_at_bound = as.integer(tau == 0))
}
d <- rbind(
  fits("balanced", "adaptive", 8, log(0.6), 0.4, 0.10, 0.04), fits("balanced", "random", 8, log(0.4), 0.4, 0.08, 0.04),
  fits("unbalanced", "adaptive", 5, log(0.5), 0.2, 0.12, 0.02), fits("unbalanced", "random", 11, log(0.5), 0.7, 0.09, 0.06),
  fits("bounds", "adaptive", 9, log(3), 1.5, 0.05, 0.06), fits("bounds", "random", 7, log(1), 1, 0.03, 0.05),
  fits("ties", "adaptive", 10, log(0.5), 0.5, 0.1, 0.05, grid = 0.1),
  fits("ties", "random", 9, log(0.4), 0.5, 0.1, 0.05, grid = 0.1),
  fits("small", "adaptive", 2, log(0.5), 0.3, 0.1, 0.03), fits("small", "random", 3, log(0.3), 0.3, 0.05, 0.03),
  fits("small", "fixed", 4, log(9), 0.1, 0.5, 0.1),
  fits("strong", "adaptive", 30, log(1.5), 0.3, 0.2, 0.05), fits("strong", "random", 25, log(0.3), 0.3, 0.05, 0.05))
# bounds: one participant who never infers (beta = 0), betas at the range's maximum 20
b <- d$dataset == "bounds"
d$beta[b & d$participant == "a03"] <- 0
d$beta[b & d$participant %in% c("a05", "r02")] <- 20
d$beta_at_bound[b & d$participant %in% c("a05", "r02")] <- 1
write.csv(d, "observer_compare_data.csv", row.names = FALSE, quote = FALSE)

out <- list()
put <- function(ds, parameter, quantity, value)
  out[[length(out) + 1]] <<- data.frame(dataset = ds, parameter = parameter, quantity = quantity,
                                        value = g17(unname(value)))
for (ds in unique(d$dataset)) {
  for (parameter in c("log beta", "tau")) {
    v <- if (parameter == "log beta") log(d$beta) else d$tau
    keep <- d$dataset == ds & d$condition %in% c("adaptive", "random") & is.finite(v)
    x <- v[keep & d$condition == "adaptive"]; y <- v[keep & d$condition == "random"]
    bound <- if (parameter == "log beta") d$beta_at_bound else d$tau_at_bound
    n1 <- length(x); n2 <- length(y)
    put(ds, parameter, "n_a", n1); put(ds, parameter, "n_b", n2); put(ds, parameter, "at_bound", sum(bound[keep]))
    w <- t.test(x, y)
    put(ds, parameter, "t", w$statistic); put(ds, parameter, "df", w$parameter); put(ds, parameter, "p", w$p.value)
    put(ds, parameter, "conf_low", w$conf.int[1]); put(ds, parameter, "conf_high", w$conf.int[2])
    put(ds, parameter, "estimate", mean(x) - mean(y))
    sp <- sqrt(((n1 - 1) * var(x) + (n2 - 1) * var(y)) / (n1 + n2 - 2))
    dd <- (mean(x) - mean(y)) / sp; h <- sqrt(1 / n1 + 1 / n2); tp <- dd / h; nu <- n1 + n2 - 2
    lo <- ncp_root(tp, nu, 0.975) * h; hi <- ncp_root(tp, nu, 0.025) * h; j <- hedges_j(nu)
    put(ds, parameter, "d", dd); put(ds, parameter, "d_low", lo); put(ds, parameter, "d_high", hi)
    put(ds, parameter, "g", dd * j); put(ds, parameter, "g_low", lo * j); put(ds, parameter, "g_high", hi * j)
    put(ds, parameter, "log_bf10", log_bf_point(tp, n1 * n2 / (n1 + n2), nu, sqrt(2) / 2))
    put(ds, parameter, "log_bf_ttestbf", extractBF(ttestBF(x, y, rscale = sqrt(2) / 2), logbf = TRUE)$bf)
    m <- suppressWarnings(wilcox.test(x, y))
    ties <- length(unique(c(x, y))) < n1 + n2
    put(ds, parameter, "W", m$statistic); put(ds, parameter, "p_mw", m$p.value)
    put(ds, parameter, "exact", as.integer(!ties && n1 < 50 && n2 < 50))
    r <- rank_biserial(x, y, ci = 0.95, verbose = FALSE)
    put(ds, parameter, "rb", r$r_rank_biserial); put(ds, parameter, "rb_low", r$CI_low)
    put(ds, parameter, "rb_high", r$CI_high)
  }
}
write.csv(do.call(rbind, out), "observer_compare_golden.csv", row.names = FALSE, quote = FALSE)
