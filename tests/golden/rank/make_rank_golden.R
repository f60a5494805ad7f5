# Golden values for feint's rank tests and reliability statistics (tests/stats/test_rank_golden.cpp,
# test_kruskal.cpp, test_reliability.cpp). Regenerate from the repository root with
#   Rscript tests/golden/rank/make_rank_golden.R
# Needs R >= 4.2 and psych. Every number is written with sprintf("%.17g") so it round-trips to the
# same double; samples are ';'-separated inside one field, groups / items '|'-separated.
suppressPackageStartupMessages(library(psych))
set.seed(20261121)
out_dir <- "tests/golden/rank"
if (!dir.exists(out_dir)) stop("run from the repository root")

g17 <- function(v) ifelse(is.na(v), "NA", sprintf("%.17g", v))
vec <- function(v) paste(g17(v), collapse = ";")
lgl <- function(v) if (is.null(v)) "NA" else if (v) "TRUE" else "FALSE"

# ---- wilcox.test: one-sample (signed rank) and two-sample (rank sum) --------------------------
rows <- list()
add_case <- function(label, x, y = NULL, mu = 0, alternative = "two.sided", correct = TRUE,
                     exact = NULL) {
  warns <- character(0)
  t <- withCallingHandlers(if (is.null(y))
    wilcox.test(x, mu = mu, alternative = alternative, correct = correct, exact = exact)
  else wilcox.test(x, y, alternative = alternative, correct = correct, exact = exact),
  warning = function(w) { warns <<- c(warns, conditionMessage(w)); invokeRestart("muffleWarning") })
  stat <- unname(t$statistic)
  xs <- x[!is.na(x)]
  if (is.null(y)) {
    d <- xs - mu
    n <- sum(d != 0)
    S <- n * (n + 1) / 2
    rb <- (stat - (S - stat)) / S              # matched-pairs rank-biserial (Kerby 2014)
    ys <- numeric(0)
  } else {
    ys <- y[!is.na(y)]
    rb <- 2 * stat / (length(xs) * length(ys)) - 1  # Glass's rank-biserial
  }
  q <- function(v, p) if (length(v)) unname(quantile(v, p)) else NA
  s <- function(v) if (length(v) > 1) sd(v) else NA
  m <- function(v) if (length(v)) mean(v) else NA
  rows[[length(rows) + 1]] <<- data.frame(
    case = label, test = if (is.null(y)) "signrank" else "ranksum", alternative = alternative,
    mu = g17(mu), correct = lgl(correct), exact_arg = lgl(exact),
    x = vec(x), y = if (is.null(y)) "" else vec(y),
    statistic = g17(stat), p_value = g17(t$p.value),
    exact = if (grepl("exact", t$method)) "TRUE" else "FALSE", method = t$method,
    warnings = paste(warns, collapse = ";"),
    rank_biserial = g17(rb), n1 = length(xs), n2 = length(ys),
    mean1 = g17(m(xs)), sd1 = g17(s(xs)), median1 = g17(q(xs, 0.5)), iqr1 = g17(q(xs, 0.75) - q(xs, 0.25)),
    mean2 = g17(m(ys)), sd2 = g17(s(ys)), median2 = g17(q(ys, 0.5)), iqr2 = g17(q(ys, 0.75) - q(ys, 0.25)))
}
likert <- function(n, centre = 4, spread = 1.5)
  pmin(7, pmax(1, round(rnorm(n, centre, spread))))
alts <- c("two.sided", "greater", "less")

for (alt in alts) {
  # Exact path: continuous, no ties, n < 50 (n = 1 included: p = 1 or 0.5).
  for (n in c(1, 2, 3, 5, 8, 12, 20, 30, 49))
    add_case(sprintf("sr_cont_n%d_%s", n, alt), rnorm(n, 0.3), mu = 0, alternative = alt)
  # Normal path because n >= 50.
  for (n in c(50, 75, 120, 200))
    add_case(sprintf("sr_cont_n%d_%s", n, alt), rnorm(n, 10.2, 2), mu = 10, alternative = alt)
  # Likert 1..7: ties, and zeros when mu is a scale point.
  for (n in c(5, 10, 20, 30, 49, 60, 100, 200)) {
    add_case(sprintf("sr_likert_n%d_mu4_%s", n, alt), likert(n, 4.4), mu = 4, alternative = alt)
    add_case(sprintf("sr_likert_n%d_mu3.5_%s", n, alt), likert(n, 3.9), mu = 3.5, alternative = alt)
  }
  # Zeros without ties among the non-zero differences.
  add_case(sprintf("sr_zeros_n12_%s", alt), c(rnorm(10, 1), 1, 1), mu = 1, alternative = alt)
  add_case(sprintf("sr_zeros_n40_%s", alt), c(rnorm(37, 2.5), 2, 2, 2), mu = 2, alternative = alt)
  # Tiny p-values: exact (2^-40) and normal (n = 200, strong shift).
  add_case(sprintf("sr_tiny_exact_n40_%s", alt), runif(40, 1, 2), mu = 0, alternative = alt)
  add_case(sprintf("sr_tiny_normal_n200_%s", alt), rnorm(200, 5), mu = 0, alternative = alt)
  # Forced paths.
  add_case(sprintf("sr_forced_normal_n15_%s", alt), rnorm(15, 0.5), mu = 0, alternative = alt, exact = FALSE)
  add_case(sprintf("sr_uncorrected_n25_%s", alt), likert(25, 4.5), mu = 4, alternative = alt, correct = FALSE)
  add_case(sprintf("sr_forced_exact_n60_%s", alt), rnorm(60, 0.2), mu = 0, alternative = alt, exact = TRUE)
  add_case(sprintf("sr_forced_exact_ties_%s", alt), c(1, 2, 2, 3, -1, 4, 5), mu = 0, alternative = alt, exact = TRUE)
}

for (alt in alts) {
  # Exact path: continuous, no ties, both n < 50.
  for (nn in list(c(1, 1), c(1, 5), c(3, 4), c(5, 10), c(10, 10), c(20, 15), c(30, 49), c(49, 49), c(49, 3)))
    add_case(sprintf("rs_cont_%dx%d_%s", nn[1], nn[2], alt), rnorm(nn[1], 0.4), rnorm(nn[2]), alternative = alt)
  # Normal path: an n >= 50.
  for (nn in list(c(50, 50), c(60, 30), c(10, 80), c(100, 120), c(200, 200)))
    add_case(sprintf("rs_cont_%dx%d_%s", nn[1], nn[2], alt), rnorm(nn[1], 0.3), rnorm(nn[2]), alternative = alt)
  # Likert: ties.
  for (nn in list(c(5, 6), c(10, 12), c(20, 20), c(30, 25), c(50, 60), c(100, 100), c(200, 150)))
    add_case(sprintf("rs_likert_%dx%d_%s", nn[1], nn[2], alt), likert(nn[1], 4.5), likert(nn[2], 4), alternative = alt)
  # Tiny p-values: complete separation (exact) and a large shift (normal).
  add_case(sprintf("rs_tiny_exact_40x45_%s", alt), runif(40, 2, 3), runif(45, 0, 1), alternative = alt)
  add_case(sprintf("rs_tiny_normal_200x180_%s", alt), rnorm(200, 3), rnorm(180), alternative = alt)
  # Forced paths.
  add_case(sprintf("rs_forced_normal_8x9_%s", alt), rnorm(8, 1), rnorm(9), alternative = alt, exact = FALSE)
  add_case(sprintf("rs_uncorrected_15x20_%s", alt), likert(15), likert(20, 3.5), alternative = alt, correct = FALSE)
  add_case(sprintf("rs_forced_exact_60x55_%s", alt), rnorm(60, 0.3), rnorm(55), alternative = alt, exact = TRUE)
}
# NaN handling: R drops NA/NaN before testing.
add_case("sr_with_nan", c(1.2, NaN, 0.4, -0.3, 2.2, 0.9), mu = 0)
add_case("rs_with_nan", c(1.2, NaN, 0.4, 2.2, 0.9), c(0.1, -0.5, NaN, 0.3))

wilcoxon <- do.call(rbind, rows)
write.csv(wilcoxon, file.path(out_dir, "wilcoxon.csv"), row.names = FALSE, quote = FALSE)

# ---- psignrank / pwilcox: the exact distributions, both tails --------------------------------
dist <- list()
for (n in c(1, 2, 5, 10, 25, 40, 49)) {
  S <- n * (n + 1) / 2
  # Non-integral q too: psignrank rounds it to the nearest integer, pwilcox floors it.
  for (q in unique(c(-1, 0, 1, 2, 2.4, 2.5, floor(S / 4), floor(S / 2), ceiling(S / 2), S - 3, S - 1, S)))
    for (lower in c(TRUE, FALSE))
      dist[[length(dist) + 1]] <- data.frame(kind = "psignrank", q = q, m = n, n = NA, lower = lgl(lower),
                                             p = g17(psignrank(q, n, lower.tail = lower)))
}
for (mn in list(c(1, 1), c(2, 3), c(4, 4), c(7, 12), c(20, 20), c(30, 45), c(49, 49), c(49, 1))) {
  m <- mn[1]; n <- mn[2]; S <- m * n
  for (q in unique(c(-1, 0, 1, 2.5, 2.6, 3, floor(S / 3), floor(S / 2), S - 4, S - 1, S)))
    for (lower in c(TRUE, FALSE))
      dist[[length(dist) + 1]] <- data.frame(kind = "pwilcox", q = q, m = m, n = n, lower = lgl(lower),
                                             p = g17(pwilcox(q, m, n, lower.tail = lower)))
}
write.csv(do.call(rbind, dist), file.path(out_dir, "distributions.csv"), row.names = FALSE, quote = FALSE)

# ---- kruskal.test(y ~ g) ---------------------------------------------------------------------
kw <- list()
add_kw <- function(label, groups) {
  y <- unlist(groups)
  g <- factor(rep(seq_along(groups), lengths(groups)))
  t <- kruskal.test(y ~ g)
  kw[[length(kw) + 1]] <<- data.frame(
    case = label, groups = paste(vapply(groups, vec, ""), collapse = "|"),
    statistic = g17(unname(t$statistic)), df = g17(unname(t$parameter)), p_value = g17(t$p.value),
    n = length(y))
}
add_kw("hollander_wolfe_k3", list(c(2.9, 3.0, 2.5, 2.6, 3.2), c(3.8, 2.7, 4.0, 2.4), c(2.8, 3.4, 3.7, 2.2, 2.0)))
add_kw("two_groups_small", list(c(2.9, 3.0, 2.5, 2.6, 3.2), c(3.8, 2.7, 4.0, 2.4)))
for (k in 2:6) {
  add_kw(sprintf("cont_k%d_n10", k), lapply(seq_len(k), function(i) rnorm(10, i / 4)))
  add_kw(sprintf("cont_k%d_unequal", k), lapply(seq_len(k), function(i) rnorm(3 + 7 * i, i / 3)))
  add_kw(sprintf("likert_k%d_n30", k), lapply(seq_len(k), function(i) likert(30, 3.5 + i / 4)))
}
add_kw("likert_k3_n200", lapply(1:3, function(i) likert(200, 3.8 + i / 5)))
add_kw("singletons", list(1.5, c(2.5, 3.1), c(0.2, 0.7, 4.4)))
add_kw("tiny_p", list(rnorm(150, 0), rnorm(150, 3), rnorm(150, 6)))
add_kw("heavy_ties", list(c(1, 1, 1, 2), c(1, 2, 2, 2), c(2, 2, 3, 3)))
write.csv(do.call(rbind, kw), file.path(out_dir, "kruskal.csv"), row.names = FALSE, quote = FALSE)

# ---- psych::alpha: raw_alpha and alpha.drop$raw_alpha (complete cases) ------------------------
al <- list()
add_alpha <- function(label, items) {
  m <- na.omit(as.data.frame(items, col.names = paste0("item", seq_along(items))))
  a <- suppressWarnings(suppressMessages(psych::alpha(m, warnings = FALSE)))
  # alpha.drop has a row per item psych kept (it deletes items without variance): align by name.
  drop <- a$alpha.drop$raw_alpha[match(names(m), rownames(a$alpha.drop))]
  al[[length(al) + 1]] <<- data.frame(
    case = label, items = paste(vapply(items, vec, ""), collapse = "|"),
    raw_alpha = g17(a$total$raw_alpha), drop = vec(drop), n = nrow(m),
    items_used = nrow(a$alpha.drop))
}
scale_items <- function(n, k, loading = 0.7, likert_scale = TRUE) {
  f <- rnorm(n)
  lapply(seq_len(k), function(j) {
    v <- loading * f + sqrt(1 - loading^2) * rnorm(n)
    if (likert_scale) pmin(7, pmax(1, round(4 + 1.5 * v))) else v
  })
}
invisible(capture.output({
  for (k in c(2, 3, 4, 5, 8)) {
    add_alpha(sprintf("likert_k%d_n30", k), scale_items(30, k))
    add_alpha(sprintf("cont_k%d_n200", k), scale_items(200, k, 0.5, FALSE))
  }
  add_alpha("likert_k4_n12_weak", scale_items(12, 4, 0.3))
  items <- scale_items(60, 4)
  items[[2]] <- 8 - items[[2]]  # an unreversed negatively keyed item: alpha falls (psych warns)
  add_alpha("likert_k4_negative_item", items)
  items <- scale_items(40, 3)
  items[[1]][c(3, 17)] <- NA
  items[[3]][c(17, 25, 31)] <- NA
  add_alpha("likert_k3_missing", items)
  add_alpha("paper_like_k4_n25", scale_items(25, 4, 0.6))
  items <- scale_items(20, 4)
  items[[3]] <- rep(5, 20)  # no variance: psych deletes the item (and warns)
  add_alpha("likert_k4_constant_item", items)
  items <- scale_items(20, 3)
  items[[1]] <- rep(4, 20)
  add_alpha("likert_k3_constant_item_leaves_two", items)
}))
write.csv(do.call(rbind, al), file.path(out_dir, "alpha.csv"), row.names = FALSE, quote = FALSE)
cat("wrote", nrow(wilcoxon), "wilcox.test cases,", length(dist), "distribution values,",
    length(kw), "kruskal.test cases,", length(al), "psych::alpha cases\n")
