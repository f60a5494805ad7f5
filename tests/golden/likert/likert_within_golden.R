# Golden values of the questionnaire compared within participants (feint/tables/likert.hpp
# `paired`, feint/tables/likert_conditions.hpp within) and of the yes/no question within
# participants (feint/stats/paired_proportions.hpp), on
#   tests/data/likert/within_two.csv    16 participants, 2 conditions (P15, P16 in one only; one
#                                       answer missing; many ties and zero differences)
#   tests/data/likert/within_three.csv  14 participants, 3 conditions (P14 not in fixed-block; two
#                                       answers missing)
#   tests/data/likert/within_yesno.csv  22 participants, 2 conditions (P22 in one only; one missing)
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

d3 <- read.csv("tests/data/likert/within_three.csv", na.strings = "", stringsAsFactors = FALSE)
conditions <- c("adaptive", "random", "fixed-block")  # the questionnaire's order
all <- paste(conditions, collapse = ", ")
for (item in items) {
  wide <- reshape(d3[, c("participant", "condition", item)], idvar = "participant", timevar = "condition",
                  direction = "wide")
  m <- as.matrix(wide[, paste0(item, ".", conditions)])
  m <- m[complete.cases(m), , drop = FALSE]
  f <- friedman.test(m)
  put("three", item, all, "", "chi2", f$statistic)
  put("three", item, all, "", "df", f$parameter)
  put("three", item, all, "", "p", f$p.value)
  put("three", item, all, "", "n", nrow(m))
  put("three", item, all, "", "W", kendalls_w(m, ci = NULL, verbose = FALSE)$Kendalls_W)
  # The same test through the formula interface on the complete blocks.
  long <- data.frame(y = c(m), condition = factor(rep(conditions, each = nrow(m))), participant = factor(rep(seq_len(nrow(m)), 3)))
  stopifnot(abs(friedman.test(y ~ condition | participant, data = long)$statistic - f$statistic) < 1e-12)
  pr <- combn(conditions, 2)
  pw <- c(); pt <- c()
  for (j in seq_len(ncol(pr))) {
    ps <- paired("three", d3, item, pr[1, j], pr[2, j])
    pw <- c(pw, ps[1]); pt <- c(pt, ps[2])
  }
  hw <- p.adjust(pw, "holm"); ht <- p.adjust(pt, "holm")
  for (j in seq_len(ncol(pr))) {
    put("three", item, pr[1, j], pr[2, j], "p_w_holm", hw[j])
    put("three", item, pr[1, j], pr[2, j], "p_t_holm", ht[j])
  }
}

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
write.csv(out, "tests/golden/likert/likert_within_golden.csv", row.names = FALSE, quote = TRUE)
