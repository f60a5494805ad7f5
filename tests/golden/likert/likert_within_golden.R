# Golden values of the questionnaire compared within participants (feint/tables/likert.hpp
# `paired`, feint/tables/likert_conditions.hpp within) and of the yes/no question within
# participants (feint/stats/paired_proportions.hpp), on
#   tests/data/likert/within_two.csv    16 participants, 2 conditions (P15, P16 in one only; one
#                                       answer missing; many ties and zero differences)
#   tests/data/likert/within_three.csv  14 participants, 3 conditions (P14 not in fixed-block; two
#                                       answers missing)
#   tests/data/likert/within_yesno.csv  22 participants, 2 conditions (P22 in one only; one missing)
# and ten data sets generated here with a fixed seed into tests/golden/likert/data/within_*.csv:
# two conditions ("two_*": complete, missing answers and absent participants, ties and zero
# differences, small, large) and three to five ("three_complete", "three_missing", "four_ties",
# "three_small", "five_unbalanced").
# R 4.2 with effectsize and BayesFactor. Run from the repository root:
#   Rscript tests/golden/likert/likert_within_golden.R
# Writes tests/golden/likert/likert_within_golden.csv: data, item, group1, group2, quantity, value.
suppressMessages({ library(effectsize); library(BayesFactor) })
out <- data.frame(data = character(), item = character(), group1 = character(), group2 = character(),
                  quantity = character(), value = character(), stringsAsFactors = FALSE)
put <- function(data, item, g1, g2, quantity, value) {
  out[nrow(out) + 1, ] <<- list(data, item, g1, g2, quantity, sprintf("%.17g", value))
}
items <- c("entertainment", "deception", "intelligence", "trust")
# Each participant's answers in conditions a and b, aligned; pairs missing either answer dropped.
pairs_of <- function(d, item, a, b) {
  da <- d[d$condition == a, c("participant", item)]
  db <- d[d$condition == b, c("participant", item)]
  m <- merge(da, db, by = "participant", suffixes = c(".a", ".b"))
  m <- m[complete.cases(m), ]
  list(x = m[[paste0(item, ".a")]], y = m[[paste0(item, ".b")]])
}
paired <- function(name, d, item, a, b) {
  p <- pairs_of(d, item, a, b)
  w <- suppressWarnings(wilcox.test(p$x, p$y, paired = TRUE))
  put(name, item, a, b, "V", w$statistic)
  put(name, item, a, b, "p_w", w$p.value)
  put(name, item, a, b, "r_rb", rank_biserial(p$x, p$y, paired = TRUE, ci = NULL)$r_rank_biserial)
  t <- t.test(p$x, p$y, paired = TRUE)
  put(name, item, a, b, "t", t$statistic)
  put(name, item, a, b, "df_t", t$parameter)
  put(name, item, a, b, "p_t", t$p.value)
  put(name, item, a, b, "d_z", mean(p$x - p$y) / sd(p$x - p$y))
  put(name, item, a, b, "bf10", exp(ttestBF(p$x, p$y, paired = TRUE, rscale = sqrt(2) / 2)@bayesFactor$bf))
  c(w$p.value, t$p.value)
}

d2 <- read.csv("tests/data/likert/within_two.csv", na.strings = "", stringsAsFactors = FALSE)
for (item in items) paired("two", d2, item, "adaptive", "random")

across <- function(name, d3) {
conditions <- unique(d3$condition)  # the questionnaire's order
all <- paste(conditions, collapse = ", ")
for (item in items) {
  wide <- reshape(d3[, c("participant", "condition", item)], idvar = "participant", timevar = "condition",
                  direction = "wide")
  m <- as.matrix(wide[, paste0(item, ".", conditions)])
  m <- m[complete.cases(m), , drop = FALSE]
  f <- friedman.test(m)
  put(name, item, all, "", "chi2", f$statistic)
  put(name, item, all, "", "df", f$parameter)
  put(name, item, all, "", "p", f$p.value)
  put(name, item, all, "", "n", nrow(m))
  put(name, item, all, "", "W", kendalls_w(m, ci = NULL, verbose = FALSE)$Kendalls_W)
  # The same test through the formula interface on the complete blocks.
  long <- data.frame(y = c(m), condition = factor(rep(conditions, each = nrow(m))),
                     participant = factor(rep(seq_len(nrow(m)), length(conditions))))
  stopifnot(abs(friedman.test(y ~ condition | participant, data = long)$statistic - f$statistic) < 1e-12)
  pr <- combn(conditions, 2)
  pw <- c(); pt <- c()
  for (j in seq_len(ncol(pr))) {
    ps <- paired(name, d3, item, pr[1, j], pr[2, j])
    pw <- c(pw, ps[1]); pt <- c(pt, ps[2])
  }
  hw <- p.adjust(pw, "holm"); ht <- p.adjust(pt, "holm")
  for (j in seq_len(ncol(pr))) {
    put(name, item, pr[1, j], pr[2, j], "p_w_holm", hw[j])
    put(name, item, pr[1, j], pr[2, j], "p_t_holm", ht[j])
  }
}
}
across("three", read.csv("tests/data/likert/within_three.csv", na.strings = "", stringsAsFactors = FALSE))

# The yes/no question within participants: the table of pairs, McNemar exact (binom.test on the
# discordant pairs) and mcnemar.test (continuity-corrected).
dy <- read.csv("tests/data/likert/within_yesno.csv", na.strings = "", stringsAsFactors = FALSE)
for (q in c("intentional", "noticed")) {
  p <- pairs_of(dy, q, "adaptive", "random")
  x <- p$x == "yes"; y <- p$y == "yes"
  b <- sum(x & !y); c <- sum(!x & y)
  bt <- binom.test(b, b + c, 0.5)
  mc <- mcnemar.test(table(factor(x, c(TRUE, FALSE)), factor(y, c(TRUE, FALSE))))
  put("yesno", q, "adaptive", "random", "pairs", length(x))
  put("yesno", q, "adaptive", "random", "b", b)
  put("yesno", q, "adaptive", "random", "c", c)
  put("yesno", q, "adaptive", "random", "p_exact", bt$p.value)
  put("yesno", q, "adaptive", "random", "or", b / c)
  put("yesno", q, "adaptive", "random", "or_low", bt$conf.int[1] / (1 - bt$conf.int[1]))
  put("yesno", q, "adaptive", "random", "or_high", bt$conf.int[2] / (1 - bt$conf.int[2]))
  put("yesno", q, "adaptive", "random", "chi2", mc$statistic)
  put("yesno", q, "adaptive", "random", "p_chi2", mc$p.value)
  put("yesno", q, "adaptive", "random", "p_a", mean(x))
  put("yesno", q, "adaptive", "random", "p_b", mean(y))
}
# Generated: each participant answers after each condition (rows in the conditions' order; the
# first participant has them all, so the file's order is the conditions' order); an answer is a
# rounded normal draw clipped to 1-7 around the participant's own level plus the condition's shift
# (sd `spread`: small spreads give ties and zero differences); `miss`: an empty answer; `absent`:
# a participant's row missing for that condition.
generate <- function(name, conditions, n, shift, spread, miss, absent) {
  level <- rnorm(n, 4, 1)
  d <- data.frame(participant = character(), condition = character(), stringsAsFactors = FALSE)
  for (i in seq_len(n)) for (j in seq_along(conditions)) {
    if (i > 1 && runif(1) < absent) next
    r <- nrow(d) + 1
    d[r, "participant"] <- sprintf("P%02d", i)
    d[r, "condition"] <- conditions[j]
    for (k in seq_along(items)) {
      y <- min(7, max(1, round(rnorm(1, level[i] + shift[j] + (k - 2.5) * 0.3, spread))))
      d[r, items[k]] <- if (runif(1) < miss) NA else y
    }
  }
  out <- d
  for (it in items) out[[it]] <- ifelse(is.na(d[[it]]), "", d[[it]])
  dir.create("tests/golden/likert/data", showWarnings = FALSE)
  write.csv(out, file.path("tests/golden/likert/data", paste0("within_", name, ".csv")), row.names = FALSE,
            quote = FALSE)
  d
}
set.seed(20260404)
c2 <- c("adaptive", "random")
c5 <- c("adaptive", "random", "fixed-block", "mirror", "none")
for (spec in list(list("two_complete", 18, c(0.8, 0), 1.2, 0, 0),
                  list("two_missing", 24, c(0.3, -0.2), 1.4, 0.08, 0.08),
                  list("two_ties", 20, c(0.2, 0), 0.45, 0.03, 0),
                  list("two_small", 7, c(1, 0), 1.3, 0, 0),
                  list("two_large", 45, c(0.4, 0), 1.3, 0.03, 0.03))) {
  d <- generate(spec[[1]], c2, spec[[2]], spec[[3]], spec[[4]], spec[[5]], spec[[6]])
  for (item in items) paired(spec[[1]], d, item, "adaptive", "random")
}
across("three_complete", generate("three_complete", c5[1:3], 15, c(1, 0, -0.5), 1.2, 0, 0))
across("three_missing", generate("three_missing", c5[1:3], 22, c(0.5, 0, 0.2), 1.4, 0.07, 0.08))
across("four_ties", generate("four_ties", c5[1:4], 16, c(0.3, 0, 0, -0.2), 0.5, 0.03, 0.04))
across("three_small", generate("three_small", c5[1:3], 6, c(1.5, 0, -1), 1.2, 0, 0))
across("five_unbalanced", generate("five_unbalanced", c5, 14, c(0.6, 0, -0.4, 0.2, 1), 1.3, 0.04, 0.1))

write.csv(out, "tests/golden/likert/likert_within_golden.csv", row.names = FALSE, quote = TRUE)
cat(sprintf("wrote %d golden values on %d data sets\n", nrow(out), length(unique(out$data))))
