# Golden values of t-test power and sample size from R's power.t.test(strict = TRUE) and
# pwr::pwr.t.test / pwr::pwr.t2n.test. Run from the repository root:
#   Rscript tests/golden/models/power_golden.R      -> tests/golden/models/power_golden.csv
# Solved quantities use uniroot with tol = 1e-13 (R's default eps^0.25 stops at ~1e-4).
# Welch rows: R has no Welch power function in base/pwr; the same noncentral-t formula as
# MESS::power_welch_t_test (ncp = delta / sqrt(sd1^2/n1 + sd2^2/n2), Welch-Satterthwaite df of the
# population variances) is written out here with R's qt/pt.
suppressPackageStartupMessages(library(pwr))
rows <- list()
add <- function(...) rows[[length(rows) + 1]] <<- data.frame(...)
fmt <- function(x) if (is.null(x) || is.na(x)) "NA" else sprintf("%.17g", x)
tol <- 1e-13

# power.t.test: solve for power, n, delta; one- and two-sided; three designs; Bonferroni m.
alt_name <- c(two.sided = "two.sided", one.sided = "greater")
for (type in c("one.sample", "two.sample", "paired")) {
  for (alt in c("two.sided", "one.sided")) {
    for (m in c(1, 20)) {
      for (cfg in list(c(n = 12, delta = 0.8, sd = 1.3), c(n = 30, delta = 0.5, sd = 1), c(n = 75, delta = 0.2, sd = 0.7))) {
        a <- 0.05 / m
        p <- power.t.test(n = cfg[["n"]], delta = cfg[["delta"]], sd = cfg[["sd"]], sig.level = a,
                          type = type, alternative = alt, strict = TRUE)$power
        add(source = "power.t.test", solve = "power", type = type, alternative = alt_name[[alt]],
            tests = m, n = fmt(cfg[["n"]]), ratio = 1, delta = fmt(cfg[["delta"]]), sd = fmt(cfg[["sd"]]),
            sd2 = "NA", welch = FALSE, power = fmt(p))
        if (p > a + 0.01 && p < 0.999) {
          pw <- max(min(p, 0.95), 0.5)
          nn <- power.t.test(power = pw, delta = cfg[["delta"]], sd = cfg[["sd"]], sig.level = a,
                             type = type, alternative = alt, strict = TRUE, tol = tol)$n
          add(source = "power.t.test", solve = "n", type = type, alternative = alt_name[[alt]], tests = m,
              n = fmt(nn), ratio = 1, delta = fmt(cfg[["delta"]]), sd = fmt(cfg[["sd"]]), sd2 = "NA",
              welch = FALSE, power = fmt(pw))
          dd <- power.t.test(power = pw, n = cfg[["n"]], sd = cfg[["sd"]], sig.level = a,
                             type = type, alternative = alt, strict = TRUE, tol = tol)$delta
          add(source = "power.t.test", solve = "delta", type = type, alternative = alt_name[[alt]],
              tests = m, n = fmt(cfg[["n"]]), ratio = 1, delta = fmt(dd), sd = fmt(cfg[["sd"]]),
              sd2 = "NA", welch = FALSE, power = fmt(pw))
        }
      }
    }
  }
}
# pwr.t.test (Cohen's d, sd = 1), including alternative = "less" (d negative in pwr's convention).
for (type in c("one.sample", "two.sample", "paired")) {
  for (alt in c("two.sided", "greater", "less")) {
    for (cfg in list(c(n = 20, d = 0.6), c(n = 45, d = 0.35))) {
      d <- if (alt == "less") -cfg[["d"]] else cfg[["d"]]
      p <- pwr.t.test(n = cfg[["n"]], d = d, sig.level = 0.05, type = type, alternative = alt)$power
      add(source = "pwr.t.test", solve = "power", type = type, alternative = alt, tests = 1,
          n = fmt(cfg[["n"]]), ratio = 1, delta = fmt(cfg[["d"]]), sd = 1, sd2 = "NA", welch = FALSE,
          power = fmt(p))
    }
  }
}
# pwr.t2n.test: unequal group sizes (Student).
for (cfg in list(c(n1 = 20, n2 = 30, d = 0.6), c(n1 = 40, n2 = 20, d = 0.4), c(n1 = 15, n2 = 45, d = 0.9))) {
  for (alt in c("two.sided", "greater")) {
    p <- pwr.t2n.test(n1 = cfg[["n1"]], n2 = cfg[["n2"]], d = cfg[["d"]], sig.level = 0.05,
                      alternative = alt)$power
    add(source = "pwr.t2n.test", solve = "power", type = "two.sample", alternative = alt, tests = 1,
        n = fmt(cfg[["n1"]]), ratio = fmt(cfg[["n2"]] / cfg[["n1"]]), delta = fmt(cfg[["d"]]), sd = 1,
        sd2 = "NA", welch = FALSE, power = fmt(p))
  }
}
# Welch (formula of MESS::power_welch_t_test with R's qt/pt), strict two-sided.
welch_power <- function(n1, n2, delta, sd1, sd2, a) {
  v1 <- sd1^2 / n1; v2 <- sd2^2 / n2
  nu <- (v1 + v2)^2 / (v1^2 / (n1 - 1) + v2^2 / (n2 - 1))
  ncp <- delta / sqrt(v1 + v2)
  q <- qt(a / 2, nu, lower.tail = FALSE)
  pt(q, nu, ncp = ncp, lower.tail = FALSE) + pt(-q, nu, ncp = ncp, lower.tail = TRUE)
}
for (cfg in list(c(n1 = 20, r = 1, delta = 0.5, sd1 = 1, sd2 = 2), c(n1 = 30, r = 2, delta = 0.3, sd1 = 0.5, sd2 = 0.8),
                 c(n1 = 12, r = 1, delta = 1, sd1 = 1, sd2 = 1))) {
  p <- welch_power(cfg[["n1"]], cfg[["r"]] * cfg[["n1"]], cfg[["delta"]], cfg[["sd1"]], cfg[["sd2"]], 0.05)
  add(source = "welch_formula", solve = "power", type = "two.sample", alternative = "two.sided", tests = 1,
      n = fmt(cfg[["n1"]]), ratio = fmt(cfg[["r"]]), delta = fmt(cfg[["delta"]]), sd = fmt(cfg[["sd1"]]),
      sd2 = fmt(cfg[["sd2"]]), welch = TRUE, power = fmt(p))
  n <- uniroot(function(n) welch_power(n, cfg[["r"]] * n, cfg[["delta"]], cfg[["sd1"]], cfg[["sd2"]], 0.05) - 0.8,
               c(2, 1e7), tol = tol, extendInt = "upX")$root
  add(source = "welch_formula", solve = "n", type = "two.sample", alternative = "two.sided", tests = 1,
      n = fmt(n), ratio = fmt(cfg[["r"]]), delta = fmt(cfg[["delta"]]), sd = fmt(cfg[["sd1"]]),
      sd2 = fmt(cfg[["sd2"]]), welch = TRUE, power = fmt(0.8))
}
res <- do.call(rbind, rows)
write.csv(res, "tests/golden/models/power_golden.csv", row.names = FALSE, quote = FALSE)
cat(nrow(res), "rows\n")
