# Golden effect-size intervals for feint (tests/stats/test_effect_size.cpp).
# Regenerate from the repository root with R 4.2 and effectsize 0.8:
#   Rscript tests/golden/effect/make_effect_golden.R tests/golden/effect
# The truth (columns low, high) is the exact root found here by uniroot(tol = 1e-15) on R's pt/pf
# with ncp (moderate t and F only, where R's noncentral distributions are accurate); the columns
# es_low, es_high are what effectsize 0.8 reports (its optim() search), kept to document its error.
suppressMessages(library(effectsize))
args <- commandArgs(trailingOnly = TRUE)
out <- if (length(args) >= 1) args[1] else "tests/golden/effect"
set.seed(15)
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))
adj <- function(ci, alt) if (alt == "two.sided") ci else 2 * ci - 1
root_t <- function(t, df, p) uniroot(function(x) pt(t, df, ncp = x) - p, c(t - 50, t + 50), tol = 1e-15)$root
root_f <- function(f, df1, df2, p) uniroot(function(x) pf(f, df1, df2, ncp = x) - p, c(0, 10 * (f * df1 + 50)), tol = 1e-15)$root
rows <- list()
add <- function(...) rows[[length(rows) + 1]] <<- data.frame(...)
for (k in 1:24) {
  n1 <- sample(c(3, 5, 10, 20, 40, 80), 1); n2 <- sample(c(4, 6, 10, 25, 60), 1)
  x <- rnorm(n1, runif(1, -1, 1.5)); y <- rnorm(n2)
  alt <- c("two.sided", "greater", "less")[1 + k %% 3]; ci <- c(0.95, 0.9, 0.99)[1 + (k %/% 3) %% 3]
  lv <- adj(ci, alt); a <- (1 - lv) / 2
  # one-sample d
  t <- unname(t.test(x)$statistic); df <- n1 - 1
  lo <- root_t(t, df, 1 - a) / sqrt(n1); hi <- root_t(t, df, a) / sqrt(n1)
  if (alt == "greater") hi <- Inf; if (alt == "less") lo <- -Inf
  e <- cohens_d(x, ci = ci, alternative = alt)
  add(kind = "d_one", a = g17(t), n1 = n1, n2 = 0, df1 = NA, df2 = NA, conf = ci, alternative = alt,
      low = g17(lo), high = g17(hi), es_low = g17(e$CI_low), es_high = g17(e$CI_high))
  # two-sample pooled d
  t <- unname(t.test(x, y, var.equal = TRUE)$statistic); df <- n1 + n2 - 2; h <- sqrt(1 / n1 + 1 / n2)
  lo <- root_t(t, df, 1 - a) * h; hi <- root_t(t, df, a) * h
  if (alt == "greater") hi <- Inf; if (alt == "less") lo <- -Inf
  e <- cohens_d(x, y, ci = ci, alternative = alt)
  add(kind = "d_two", a = g17(t), n1 = n1, n2 = n2, df1 = NA, df2 = NA, conf = ci, alternative = alt,
      low = g17(lo), high = g17(hi), es_low = g17(e$CI_low), es_high = g17(e$CI_high))
  # eta squared from F (one-way ANOVA of k groups), effectsize's default alternative "greater"
  kk <- sample(2:5, 1); nn <- sample(c(4, 8, 15, 30), 1)
  grp <- factor(rep(seq_len(kk), each = nn)); yv <- rnorm(kk * nn, as.numeric(grp) * runif(1, 0, 0.8))
  tab <- anova(lm(yv ~ grp)); f <- tab$`F value`[1]; d1 <- tab$Df[1]; d2 <- tab$Df[2]
  alt2 <- if (k %% 4 == 0) "two.sided" else "greater"
  lv <- adj(ci, alt2); a <- (1 - lv) / 2
  lo <- if (pf(f, d1, d2) > 1 - a) { r <- root_f(f, d1, d2, 1 - a); r / (r + d2) } else 0
  hi <- if (alt2 == "greater") 1 else if (pf(f, d1, d2) > a) { r <- root_f(f, d1, d2, a); r / (r + d2) } else 0
  e <- F_to_eta2(f, d1, d2, ci = ci, alternative = alt2)
  add(kind = "eta2", a = g17(f), n1 = 0, n2 = 0, df1 = d1, df2 = d2, conf = ci, alternative = alt2,
      low = g17(lo), high = g17(hi), es_low = g17(e$CI_low), es_high = g17(e$CI_high))
  # rank-biserial (two-sample and one-sample, no ties): effectsize's own interval is exact (closed form)
  e <- rank_biserial(x, y, ci = ci, alternative = alt)
  add(kind = "rb_two", a = g17(e$r_rank_biserial), n1 = n1, n2 = n2, df1 = NA, df2 = NA, conf = ci,
      alternative = alt, low = g17(e$CI_low), high = g17(e$CI_high), es_low = g17(e$CI_low), es_high = g17(e$CI_high))
  e <- rank_biserial(x, ci = ci, alternative = alt)
  add(kind = "rb_one", a = g17(e$r_rank_biserial), n1 = n1, n2 = 0, df1 = NA, df2 = NA, conf = ci,
      alternative = alt, low = g17(e$CI_low), high = g17(e$CI_high), es_low = g17(e$CI_low), es_high = g17(e$CI_high))
}
res <- do.call(rbind, rows)
write.csv(res, file.path(out, "effect_golden.csv"), row.names = FALSE, quote = FALSE)
num <- function(v) suppressWarnings(as.numeric(v))
w <- pmax(num(res$high) - num(res$low), 1e-300); w[!is.finite(w)] <- NA
off <- pmax(abs(num(res$es_low) - num(res$low)), abs(num(res$es_high) - num(res$high)), na.rm = TRUE)
for (kd in unique(res$kind)) {
  i <- res$kind == kd
  cat(kd, ": max |effectsize - exact| =", signif(max(off[i], na.rm = TRUE), 3),
      "; as a share of the width =", signif(max(off[i] / w[i], na.rm = TRUE), 3), "\n")
}
