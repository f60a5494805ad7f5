# Golden JZS Bayes factors for feint (tests/stats/test_bayes_factor.cpp).
# Regenerate from the repository root with R 4.2:
#   Rscript tests/golden/bayes/make_bf_golden.R tests/golden/bayes
# Writes bf_golden.csv: one row per case, log BF (natural log) of H1 (delta in [lo, hi], Cauchy prior
# with scale r truncated to the interval) against the point null delta = 0, and of the complement.
#
# The truth is the definition, integrated here with integrate(rel.tol = 1e-12); ttestBF is only a
# cross-check (column ttestbf_log_bf, and its own error estimate ttestbf_error):
#  * point null, two-sided: Rouder et al. (2009), eq. (1), with g ~ inverse-gamma(1/2, r^2/2):
#      BF10 = int_0^inf (1+N g)^(-1/2) (1 + t^2/((1+N g) nu))^(-(nu+1)/2) r/sqrt(2 pi) g^(-3/2)
#             exp(-r^2/(2g)) dg / (1 + t^2/nu)^(-(nu+1)/2)
#    integrated over x = log g.
#  * interval [lo, hi]: BF = int_lo^hi p(t | delta) cauchy(delta; r) d delta / (P(lo<delta<hi) p(t | 0)),
#    substituting delta = r tan(theta) (the Cauchy CDF), so the prior is uniform in theta; the
#    noncentral t likelihood p(t | delta) = dt(t, nu, ncp = delta sqrt(N)) is NOT taken from R's dt
#    (it loses accuracy in the far tail) but integrated from its definition:
#      p(t | delta) = int_0^inf dnorm(t s - delta sqrt(N)) s h(s) ds,  s = sqrt(V / nu), V ~ chisq(nu),
#    h(s) = 2 nu s dchisq(nu s^2, nu).
# One-sample / paired: N = n, nu = n - 1. Two-sample: N = n1 n2 / (n1 + n2), nu = n1 + n2 - 2.
suppressMessages(library(BayesFactor))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) >= 1) args[1] else "tests/golden/bayes"
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
tol <- 1e-12

log_bf_point <- function(t, N, nu, r) {
  lnull <- -(nu + 1) / 2 * log1p(t^2 / nu)
  lf <- function(x) {
    g <- exp(x)
    -0.5 * log1p(N * g) - (nu + 1) / 2 * log1p(t^2 / ((1 + N * g) * nu)) +
      log(r) - 0.5 * log(2 * pi) - 1.5 * x - r^2 / (2 * g) + x - lnull
  }
  # the maximum, then integrate exp(lf - max) over pieces around it (the integrand is smooth in x)
  xs <- seq(-40, 40, by = 0.05); lv <- lf(xs); m <- max(lv); xm <- xs[which.max(lv)]
  br <- c(-Inf, xm + seq(-40, 40, by = 2), Inf)
  tot <- 0
  for (k in seq_len(length(br) - 1)) {
    tot <- tot + integrate(function(x) exp(lf(x) - m), br[k], br[k + 1], rel.tol = tol,
                           abs.tol = 0, subdivisions = 1000L)$value
  }
  m + log(tot)
}

# log of p(t | delta) / p(t | 0) for a vector of delta.
log_lik_ratio <- function(t, N, nu, delta) {
  l0 <- dt(t, nu, log = TRUE)  # central t density: closed form, accurate
  sapply(delta, function(d) {
    lam <- d * sqrt(N)
    # s h(s) = 2 nu s^2 dchisq(nu s^2, nu), in logs written out (finite at s -> 0 for nu = 1)
    lh <- function(s) ifelse(s <= 0, -Inf, dnorm(t * s - lam, log = TRUE) + log(2 * nu) +
      (nu / 2 - 1) * log(nu) + nu * log(s) - nu * s^2 / 2 - (nu / 2) * log(2) - lgamma(nu / 2))
    # peak of the integrand in s, in closed form: d/ds [-(t s - lam)^2/2 + nu log s - nu s^2/2] = 0
    # gives (t^2 + nu) s^2 - t lam s - nu = 0; its curvature gives the width.
    sm <- (t * lam + sqrt(t^2 * lam^2 + 4 * nu * (t^2 + nu))) / (2 * (t^2 + nu))
    wid <- 1 / sqrt(t^2 + nu / sm^2 + nu)
    m <- lh(sm)
    br <- sort(unique(c(0, pmax(0, sm + wid * seq(-40, 40, by = 2)), Inf)))
    tot <- 0
    for (k in seq_len(length(br) - 1)) {
      tot <- tot + integrate(function(s) exp(lh(s) - m), br[k], br[k + 1], rel.tol = tol,
                             abs.tol = 0, subdivisions = 1000L, stop.on.error = FALSE)$value
    }
    m + log(tot) - l0
  })
}

log_bf_interval <- function(t, N, nu, r, lo, hi) {
  a <- atan(lo / r); b <- atan(hi / r)
  dhat <- t / sqrt(N)  # likelihood peak
  th <- atan(dhat / r)
  # width of the likelihood in theta: d delta / d theta = r / cos^2
  wd <- (1 / sqrt(N)) * cos(th)^2 / r
  cand <- th + wd * seq(-40, 40, by = 4)
  br <- sort(unique(c(a, cand[cand > a & cand < b], b)))
  # scale: the log ratio at the peak (clamped into the interval)
  tc <- min(max(th, a + 1e-12), b - 1e-12)
  m <- log_lik_ratio(t, N, nu, r * tan(tc))
  tot <- 0
  for (k in seq_len(length(br) - 1)) {
    tot <- tot + integrate(function(x) exp(log_lik_ratio(t, N, nu, r * tan(x)) - m),
                           br[k], br[k + 1], rel.tol = tol, abs.tol = 0, subdivisions = 1000L)$value
  }
  m + log(tot / (b - a))
}

cases <- list()
add <- function(kind, t, n1, n2, r, lo, hi) cases[[length(cases) + 1]] <<- list(kind = kind, t = t, n1 = n1, n2 = n2, r = r, lo = lo, hi = hi)
rs <- sqrt(2) / 2
# two-sided point null
for (n in c(2, 3, 5, 10, 30, 100, 500)) for (t in c(0, 0.5, -1.3, 2.2, 4, -7, 12, 25)) add("one_sample", t, n, 0, rs, -Inf, Inf)
for (nn in list(c(2, 2), c(3, 5), c(15, 15), c(30, 30), c(250, 250), c(40, 7))) for (t in c(0, 1, -2.5, 5, 21)) add("two_sample", t, nn[1], nn[2], rs, -Inf, Inf)
for (r in c(0.5, 1, sqrt(2))) for (t in c(0.3, 3, -22)) add("one_sample", t, 20, 0, r, -Inf, Inf)
# one-sided and interval
for (n in c(2, 10, 30, 500)) for (t in c(-2, 0.7, 3, 6, 22)) {
  add("one_sample", t, n, 0, rs, 0, Inf); add("one_sample", t, n, 0, rs, -Inf, 0)
}
for (nn in list(c(3, 4), c(30, 30), c(250, 250))) for (t in c(-1.5, 2.5, 8, -21)) add("two_sample", t, nn[1], nn[2], rs, 0, Inf)
for (n in c(5, 30, 500)) for (t in c(0.2, 1.5, 4, 23)) add("one_sample", t, n, 0, rs, -0.1, 0.1)
for (nn in list(c(30, 30), c(250, 250))) for (t in c(0.5, -3, 21)) add("two_sample", t, nn[1], nn[2], 1, -0.2, 0.2)

rows <- lapply(cases, function(cs) {
  if (cs$kind == "one_sample") { N <- cs$n1; nu <- cs$n1 - 1 } else {
    N <- cs$n1 * cs$n2 / (cs$n1 + cs$n2); nu <- cs$n1 + cs$n2 - 2 }
  full <- log_bf_point(cs$t, N, nu, cs$r)
  if (is.infinite(cs$lo) && is.infinite(cs$hi)) { li <- full; lc <- NA } else {
    li <- log_bf_interval(cs$t, N, nu, cs$r, cs$lo, cs$hi)
    # the complement: BF_full = P(I) BF_I + (1 - P(I)) BF_C
    pI <- (atan(cs$hi / cs$r) - atan(cs$lo / cs$r)) / pi
    lc <- log((exp(full) - pI * exp(li)) / (1 - pI))
    if (!is.finite(lc) || exp(li - full) * pI > 0.999) {
      # cancellation: integrate the complement directly
      if (is.infinite(cs$lo)) lc <- log_bf_interval(cs$t, N, nu, cs$r, cs$hi, Inf)
      else if (is.infinite(cs$hi)) lc <- log_bf_interval(cs$t, N, nu, cs$r, -Inf, cs$lo)
      else {
        pl <- (atan(cs$lo / cs$r) + pi / 2) / pi; ph <- (pi / 2 - atan(cs$hi / cs$r)) / pi
        lc <- log((pl * exp(log_bf_interval(cs$t, N, nu, cs$r, -Inf, cs$lo)) +
                   ph * exp(log_bf_interval(cs$t, N, nu, cs$r, cs$hi, Inf))) / (pl + ph))
      }
    }
  }
  # ttestBF cross-check (its MC/quadrature error estimate in 'error')
  ni <- if (is.infinite(cs$lo) && is.infinite(cs$hi)) NULL else c(cs$lo, cs$hi)
  tb <- tryCatch({
    b <- if (cs$kind == "one_sample") ttest.tstat(cs$t, cs$n1, rscale = cs$r, nullInterval = ni, complement = FALSE, simple = FALSE)
         else ttest.tstat(cs$t, cs$n1, cs$n2, rscale = cs$r, nullInterval = ni, complement = FALSE, simple = FALSE)
    c(b$bf, b$properror)
  }, error = function(e) c(NA, NA))
  data.frame(kind = cs$kind, t = g17(cs$t), n1 = cs$n1, n2 = cs$n2, r = g17(cs$r), lo = g17(cs$lo),
             hi = g17(cs$hi), log_bf = g17(li), log_bf_complement = g17(lc),
             ttestbf_log_bf = g17(tb[1]), ttestbf_error = g17(tb[2]))
})
res <- do.call(rbind, rows)
write.csv(res, file.path(out, "bf_golden.csv"), row.names = FALSE, quote = FALSE)
rel <- abs(as.numeric(res$ttestbf_log_bf) - as.numeric(res$log_bf))
cat("cases:", nrow(res), " max |log BF - ttestBF log BF|:", max(rel, na.rm = TRUE), "\n")
