# Golden values of the yes/no questions compared between conditions (feint/tables/yes_no.hpp):
# two conditions and three or more, between and within participants, on 21 generated data sets
# (tests/golden/yesno/data/*.csv, written by this script): balanced and unbalanced conditions,
# missing answers, a condition without any answer, conditions where everybody answers alike,
# participants left out of some conditions (within), ties. R 4.2 with effectsize 0.8.
#   between, 2 conditions : fisher.test, prop.test (Yates), binom.test / prop.test intervals
#   between, 3+ conditions: fisher.test(table) (FEXACT), chisq.test(table, correct = FALSE),
#                           effectsize::cramers_v (adjust = TRUE, the default, and FALSE), then every
#                           pair with fisher.test and prop.test, p.adjust "holm" over the pairs
#   within, 2 conditions  : binom.test on the discordant pairs (McNemar exact), mcnemar.test
#   within, 3+ conditions : Cochran's Q as friedman.test on the 0/1 answers of the participants who
#                           answered in every condition (checked against Cochran's formula here),
#                           then every pair as within 2, p.adjust "holm" over the pairs
# effectsize finds the ncp of Cramér's V's interval with optim (abstol 1e-9): V_low is its number,
# V_low_exact the root of pchisq(X2, df, ncp) = 0.95 by uniroot at full precision.
# fisher.test's odds ratio and interval come from uniroot at tol 1.2e-4 (docs/yes-no.md).
# Run from the repository root:  Rscript tests/golden/yesno/yesno_conditions_golden.R
# Writes tests/golden/yesno/yesno_conditions_golden.csv: data, question, group1, group2, quantity, value.
suppressMessages(library(effectsize))
out_dir <- "tests/golden/yesno"
if (!dir.exists(out_dir)) stop("run from the repository root")
dir.create(file.path(out_dir, "data"), showWarnings = FALSE)
questions <- c("intentional", "noticed")
rows <- list()
put <- function(data, q, g1, g2, quantity, value) {
  rows[[length(rows) + 1]] <<- data.frame(data = data, question = q, group1 = g1, group2 = g2,
                                          quantity = quantity, value = sprintf("%.17g", value))
}
answer <- function(x) ifelse(is.na(x), "", ifelse(x == 1, "yes", "no"))

# --- data ------------------------------------------------------------------------------------------
# Between: one row per participant; p[c, q] = probability of yes; miss = probability of no answer.
make_between <- function(name, conditions, sizes, p, miss = 0, fixed = NULL) {
  d <- data.frame(participant = character(), condition = character(), stringsAsFactors = FALSE)
  k <- 0
  for (i in seq_along(conditions)) for (j in seq_len(sizes[i])) {
    k <- k + 1
    d[k, "participant"] <- sprintf("P%03d", k)
    d[k, "condition"] <- conditions[i]
  }
  for (qi in seq_along(questions)) {
    pr <- p[match(d$condition, conditions), qi]
    y <- rbinom(nrow(d), 1, pr)
    y[runif(nrow(d)) < miss] <- NA
    d[[questions[qi]]] <- y
  }
  if (!is.null(fixed)) d <- fixed(d)
  out <- d
  for (q in questions) out[[q]] <- answer(d[[q]])
  write.csv(out, file.path(out_dir, "data", paste0(name, ".csv")), row.names = FALSE, quote = FALSE)
  d
}
# Within: each participant answers after each condition (rows in the conditions' order); a
# participant's leaning (shared by the conditions) makes the answers related; `absent` drops rows.
make_within <- function(name, conditions, n, shift, miss = 0, absent = 0) {
  d <- data.frame(participant = character(), condition = character(), stringsAsFactors = FALSE)
  lean <- rnorm(n, 0, 1.5)
  ys <- list()
  k <- 0
  for (i in seq_len(n)) for (j in seq_along(conditions)) {
    if (i > 1 && runif(1) < absent) next  # the first participant sets the conditions' order
    k <- k + 1
    d[k, "participant"] <- sprintf("P%02d", i)
    d[k, "condition"] <- conditions[j]
    for (qi in seq_along(questions)) {
      y <- rbinom(1, 1, plogis(lean[i] + shift[j, qi]))
      if (runif(1) < miss) y <- NA
      ys[[questions[qi]]][k] <- y
    }
  }
  for (q in questions) d[[q]] <- ys[[q]]
  out <- d
  for (q in questions) out[[q]] <- answer(d[[q]])
  write.csv(out, file.path(out_dir, "data", paste0(name, ".csv")), row.names = FALSE, quote = FALSE)
  d
}

# --- the statistics ------------------------------------------------------------------------------
exact_ncp <- function(x2, df, p) {
  if (pchisq(x2, df) <= p) return(0)
  uniroot(function(ncp) pchisq(x2, df, ncp = ncp) - p, c(0, max(10, 4 * x2)), tol = 1e-15)$root
}
v_of <- function(x2, n, r, adjust) {
  k <- if (adjust) r - (r - 1)^2 / (n - 1) else r
  l <- if (adjust) 2 - 1 / (n - 1) else 2
  phi2 <- x2 / n
  sqrt(if (adjust) max(0, phi2 - (r - 1) / (n - 1)) else phi2) / sqrt(min(k, l) - 1)
}
proportions <- function(name, q, g, y) {
  y <- y[!is.na(y)]
  put(name, q, g, "", "yes", sum(y)); put(name, q, g, "", "n", length(y))
  if (length(y) == 0) return()
  b <- binom.test(sum(y), length(y))$conf.int
  w <- suppressWarnings(prop.test(sum(y), length(y), correct = FALSE))$conf.int
  put(name, q, g, "", "exact_low", b[1]); put(name, q, g, "", "exact_high", b[2])
  put(name, q, g, "", "wilson_low", w[1]); put(name, q, g, "", "wilson_high", w[2])
}
pair_between <- function(name, q, a, b, ya, yb) {
  ya <- ya[!is.na(ya)]; yb <- yb[!is.na(yb)]
  if (length(ya) == 0 || length(yb) == 0) return(c(NA, NA))
  m <- matrix(c(sum(ya), sum(yb), length(ya) - sum(ya), length(yb) - sum(yb)), 2)
  f <- fisher.test(m)
  put(name, q, a, b, "fisher_p", f$p.value)
  if (is.finite(f$estimate) && f$estimate > 0) put(name, q, a, b, "or", f$estimate)
  put(name, q, a, b, "or_low", f$conf.int[1])
  if (is.finite(f$conf.int[2])) put(name, q, a, b, "or_high", f$conf.int[2])
  pp <- NA
  if (sum(m[, 1]) > 0 && sum(m[, 2]) > 0) {
    pt <- suppressWarnings(prop.test(c(sum(ya), sum(yb)), c(length(ya), length(yb))))
    put(name, q, a, b, "x2_yates", pt$statistic); put(name, q, a, b, "prop_p", pt$p.value)
    put(name, q, a, b, "diff_low", pt$conf.int[1]); put(name, q, a, b, "diff_high", pt$conf.int[2])
    pp <- pt$p.value
  }
  c(f$p.value, pp)
}
between <- function(name, d, conditions) {
  all <- paste(conditions, collapse = ", ")
  for (q in questions) {
    for (g in conditions) proportions(name, q, g, d[[q]][d$condition == g])
    if (length(conditions) > 2) {
      keep <- !is.na(d[[q]])
      tab <- table(factor(d$condition[keep], conditions), factor(d[[q]][keep], c(1, 0)))
      f <- fisher.test(tab, workspace = 2e7)
      put(name, q, all, "", "fisher_p", f$p.value)
      tab <- tab[rowSums(tab) > 0, , drop = FALSE]  # feint leaves conditions without answers out
      n <- sum(tab)
      if (all(colSums(tab) > 0)) {
        x <- suppressWarnings(chisq.test(tab, correct = FALSE))
        put(name, q, all, "", "n", n)
        put(name, q, all, "", "chi2", x$statistic); put(name, q, all, "", "df", x$parameter)
        put(name, q, all, "", "chi2_p", x$p.value)
        v <- cramers_v(tab, verbose = FALSE)                       # adjust = TRUE, ci 0.95 greater
        put(name, q, all, "", "V", v$Cramers_v_adjusted); put(name, q, all, "", "V_low", v$CI_low)
        vu <- cramers_v(tab, adjust = FALSE, verbose = FALSE)
        put(name, q, all, "", "V_unadjusted", vu$Cramers_v); put(name, q, all, "", "V_unadjusted_low", vu$CI_low)
        r <- nrow(tab); x2 <- unname(x$statistic)
        stopifnot(abs(v_of(x2, n, r, TRUE) - v$Cramers_v_adjusted) < 1e-12)
        put(name, q, all, "", "V_low_exact", v_of(exact_ncp(x2, r - 1, 0.95), n, r, TRUE))
        put(name, q, all, "", "V_unadjusted_low_exact", v_of(exact_ncp(x2, r - 1, 0.95), n, r, FALSE))
      }
    }
    pr <- combn(conditions, 2)
    ps <- sapply(seq_len(ncol(pr)), function(j) pair_between(name, q, pr[1, j], pr[2, j],
      d[[q]][d$condition == pr[1, j]], d[[q]][d$condition == pr[2, j]]))
    if (length(conditions) > 2) {
      hf <- p.adjust(ps[1, ], "holm"); hp <- p.adjust(ps[2, ], "holm")
      for (j in seq_len(ncol(pr))) {
        if (!is.na(hf[j])) put(name, q, pr[1, j], pr[2, j], "fisher_p_holm", hf[j])
        if (!is.na(hp[j])) put(name, q, pr[1, j], pr[2, j], "prop_p_holm", hp[j])
      }
    }
  }
}
pairs_of <- function(d, q, a, b) {
  da <- d[d$condition == a, c("participant", q)]; db <- d[d$condition == b, c("participant", q)]
  m <- merge(da, db, by = "participant", suffixes = c(".a", ".b"))
  m <- m[complete.cases(m), ]
  list(x = m[[paste0(q, ".a")]] == 1, y = m[[paste0(q, ".b")]] == 1)
}
pair_within <- function(name, q, d, a, b) {
  p <- pairs_of(d, q, a, b)
  bb <- sum(p$x & !p$y); cc <- sum(!p$x & p$y)
  if (bb + cc == 0) return(c(NA, NA))  # no discordant pair: feint says not computable
  put(name, q, a, b, "pairs", length(p$x)); put(name, q, a, b, "b", bb); put(name, q, a, b, "c", cc)
  bt <- binom.test(bb, bb + cc, 0.5)
  mc <- mcnemar.test(table(factor(p$x, c(TRUE, FALSE)), factor(p$y, c(TRUE, FALSE))))
  put(name, q, a, b, "p_exact", bt$p.value)
  if (cc > 0) put(name, q, a, b, "or", bb / cc)
  put(name, q, a, b, "or_low", bt$conf.int[1] / (1 - bt$conf.int[1]))
  if (bt$conf.int[2] < 1) put(name, q, a, b, "or_high", bt$conf.int[2] / (1 - bt$conf.int[2]))
  put(name, q, a, b, "chi2", mc$statistic); put(name, q, a, b, "p_chi2", mc$p.value)
  put(name, q, a, b, "p_a", mean(p$x)); put(name, q, a, b, "p_b", mean(p$y))
  c(bt$p.value, mc$p.value)
}
within <- function(name, d, conditions) {
  all <- paste(conditions, collapse = ", ")
  for (q in questions) {
    for (g in conditions) proportions(name, q, g, d[[q]][d$condition == g])
    if (length(conditions) > 2) {
      wide <- reshape(d[, c("participant", "condition", q)], idvar = "participant", timevar = "condition",
                      direction = "wide")
      m <- as.matrix(wide[, paste0(q, ".", conditions)])
      m <- m[complete.cases(m), , drop = FALSE]
      G <- colSums(m); L <- rowSums(m); N <- sum(m); C <- ncol(m)
      if (C * N - sum(L^2) > 0) {  # else every participant answered alike: not computable
        put(name, q, all, "", "n", nrow(m))
        f <- friedman.test(m)
        Q <- (C - 1) * (C * sum(G^2) - N^2) / (C * N - sum(L^2))   # Cochran (1950)
        stopifnot(abs(Q - f$statistic) < 1e-12 * max(1, Q))
        put(name, q, all, "", "Q", f$statistic); put(name, q, all, "", "df", f$parameter)
        put(name, q, all, "", "p", f$p.value)
      }
    }
    pr <- combn(conditions, 2)
    ps <- sapply(seq_len(ncol(pr)), function(j) pair_within(name, q, d, pr[1, j], pr[2, j]))
    if (length(conditions) > 2) {
      he <- p.adjust(ps[1, ], "holm"); hc <- p.adjust(ps[2, ], "holm")
      for (j in seq_len(ncol(pr))) {
        if (!is.na(he[j])) put(name, q, pr[1, j], pr[2, j], "p_exact_holm", he[j])
        if (!is.na(hc[j])) put(name, q, pr[1, j], pr[2, j], "p_chi2_holm", hc[j])
      }
    }
  }
}

# --- the data sets -------------------------------------------------------------------------------
set.seed(20260401)
c2 <- c("adaptive", "random")
c3 <- c("adaptive", "random", "fixed-block")
c4 <- c("adaptive", "random", "fixed-block", "mirror")
c5 <- c("adaptive", "random", "fixed-block", "mirror", "none")
pm <- function(...) matrix(c(...), ncol = 2, byrow = TRUE)
# Between, two conditions.
between("b2_balanced", make_between("b2_balanced", c2, c(15, 15), pm(0.6, 0.4, 0.3, 0.5)), c2)
between("b2_unbalanced_missing", make_between("b2_unbalanced_missing", c2, c(9, 23), pm(0.8, 0.5, 0.35, 0.5),
                                              miss = 0.15), c2)
between("b2_small", make_between("b2_small", c2, c(4, 6), pm(0.9, 0.5, 0.2, 0.5)), c2)
between("b2_all_yes", make_between("b2_all_yes", c2, c(12, 10), pm(1, 0.5, 0.5, 0.5)), c2)
between("b2_large", make_between("b2_large", c2, c(60, 45), pm(0.55, 0.3, 0.35, 0.6), miss = 0.05), c2)
# Between, three or more conditions.
between("b3_balanced", make_between("b3_balanced", c3, c(12, 12, 12), pm(0.7, 0.5, 0.4, 0.5, 0.6, 0.5)), c3)
between("b3_unbalanced_missing", make_between("b3_unbalanced_missing", c3, c(8, 15, 11),
                                              pm(0.8, 0.3, 0.4, 0.6, 0.2, 0.5), miss = 0.12), c3)
between("b4_strong", make_between("b4_strong", c4, c(5, 9, 14, 7), pm(0.95, 0.5, 0.2, 0.5, 0.1, 0.6, 0.6, 0.4)), c4)
# Five small conditions: one answers yes throughout, one no throughout (ties of the support).
between("b5_extremes", make_between("b5_extremes", c5, c(4, 6, 5, 3, 6), pm(1, 0.5, 0, 0.5, 0.5, 0.5, 0.5, 0.5,
                                                                          0.5, 0.5)), c5)
# A condition where nobody answered "noticed": left out of the omnibus tests.
between("b3_unanswered", make_between("b3_unanswered", c3, c(10, 7, 9), pm(0.6, 0.5, 0.2, 0.5, 0.7, 0.5),
                                      fixed = function(d) { d$noticed[d$condition == "random"] <- NA; d }), c3)
between("b5_large", make_between("b5_large", c5, c(30, 26, 34, 22, 28), pm(0.6, 0.5, 0.4, 0.5, 0.5, 0.45,
                                                                            0.7, 0.5, 0.35, 0.55), miss = 0.03), c5)
# Within, two conditions.
sh <- function(...) matrix(c(...), ncol = 2, byrow = TRUE)
within("w2_complete", make_within("w2_complete", c2, 20, sh(0.8, 0, -0.4, 0)), c2)
within("w2_missing", make_within("w2_missing", c2, 25, sh(1.2, 0.3, -0.6, 0), miss = 0.08, absent = 0.06), c2)
within("w2_small", make_within("w2_small", c2, 8, sh(0, 0, 0.5, 0)), c2)
within("w2_large", make_within("w2_large", c2, 60, sh(0.7, -0.2, 0, 0.3), miss = 0.03, absent = 0.02), c2)
within("w2_ties", make_within("w2_ties", c2, 15, sh(3, 3, 3, -3)), c2)
# Within, three or more conditions.
within("w3_complete", make_within("w3_complete", c3, 18, sh(1, 0, 0, 0, -1, 0.5)), c3)
within("w3_missing", make_within("w3_missing", c3, 24, sh(1.5, 0.2, -0.5, 0, 0, -0.4), miss = 0.07, absent = 0.08), c3)
within("w4_unbalanced", make_within("w4_unbalanced", c4, 16, sh(0.5, 1, -0.5, 0, 1.5, -1, -1, 0), miss = 0.05,
                                    absent = 0.12), c4)
within("w5_ties", make_within("w5_ties", c5, 12, sh(2, -3, 2, -3, 2, -3, 2.5, 3, -2, -3), miss = 0.04), c5)
# A strong effect on many answers: the bias-corrected V's lower bound above 0.
between("b3_strong", make_between("b3_strong", c3, c(40, 38, 42), pm(0.85, 0.5, 0.3, 0.5, 0.55, 0.45)), c3)

out <- do.call(rbind, rows)
write.csv(out, file.path(out_dir, "yesno_conditions_golden.csv"), row.names = FALSE, quote = TRUE)
cat(sprintf("wrote %d golden values on %d data sets; %s\n", nrow(out), length(unique(out$data)), R.version.string))
