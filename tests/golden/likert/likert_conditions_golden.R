# Golden values of the questionnaire across three conditions (feint/tables/likert_conditions.hpp)
# on tests/data/likert/three_conditions.csv: 28 respondents in adaptive, random and fixed-block
# (unbalanced: 9, 10, 9), one answer missing. R 4.2 with effectsize.
# Run from the repository root:  Rscript tests/golden/likert/likert_conditions_golden.R
# Writes tests/golden/likert/likert_conditions_golden.csv: item, group1, group2, quantity, value.
suppressMessages(library(effectsize))
d <- read.csv("tests/data/likert/three_conditions.csv", na.strings = "", stringsAsFactors = FALSE)
conditions <- c("adaptive", "random", "fixed-block")   # the questionnaire's order
items <- c("entertainment", "deception", "intelligence", "trust")
out <- data.frame(item = character(), group1 = character(), group2 = character(),
                  quantity = character(), value = character(), stringsAsFactors = FALSE)
put <- function(item, g1, g2, quantity, value) {
  out[nrow(out) + 1, ] <<- list(item, g1, g2, quantity, sprintf("%.17g", value))
}
for (item in items) {
  keep <- !is.na(d[[item]])
  y <- d[[item]][keep]
  g <- factor(d$condition[keep], levels = conditions)
  k <- kruskal.test(y ~ g)
  all <- paste(conditions, collapse = ", ")
  put(item, all, "", "H", k$statistic)
  put(item, all, "", "df", k$parameter)
  put(item, all, "", "p", k$p.value)
  put(item, all, "", "epsilon2", rank_epsilon_squared(y, g, ci = NULL)$rank_epsilon_squared)
  # Every pair: Mann-Whitney with Holm over the item's pairs (pairwise.wilcox.test), Welch t with Holm.
  pw <- suppressWarnings(pairwise.wilcox.test(y, g, p.adjust.method = "holm"))$p.value
  pairs <- combn(conditions, 2)
  raw_t <- c()
  for (j in seq_len(ncol(pairs))) {
    a <- pairs[1, j]; b <- pairs[2, j]
    x1 <- y[g == a]; x2 <- y[g == b]
    w <- suppressWarnings(wilcox.test(x1, x2))
    put(item, a, b, "W", w$statistic)
    put(item, a, b, "p_mw", w$p.value)
    # pairwise.wilcox.test's matrix: rows are the later levels, columns the earlier ones.
    put(item, a, b, "p_mw_holm", pw[b, a])
    t <- t.test(x1, x2)
    put(item, a, b, "t", t$statistic)
    put(item, a, b, "df_t", t$parameter)
    raw_t <- c(raw_t, t$p.value)
  }
  adj_t <- p.adjust(raw_t, "holm")
  for (j in seq_len(ncol(pairs))) put(item, pairs[1, j], pairs[2, j], "p_t_holm", adj_t[j])
}
write.csv(out, "tests/golden/likert/likert_conditions_golden.csv", row.names = FALSE, quote = TRUE)
