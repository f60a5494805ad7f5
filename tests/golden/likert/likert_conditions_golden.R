# Golden values of the questionnaire across three or more conditions (feint/tables/likert_conditions.hpp)
# on six data sets: tests/data/likert/three_conditions.csv ("three": 28 respondents in adaptive, random
# and fixed-block, unbalanced 9, 10, 9, one answer missing) and five generated here with a fixed seed
# into tests/golden/likert/data/conditions_*.csv (balanced; unbalanced with missing answers; four
# conditions with many ties; five small conditions; a large study with an effect). R 4.2 with effectsize.
# Run from the repository root:  Rscript tests/golden/likert/likert_conditions_golden.R
# Writes tests/golden/likert/likert_conditions_golden.csv: data, item, group1, group2, quantity, value.
suppressMessages(library(effectsize))
items <- c("entertainment", "deception", "intelligence", "trust")
rows <- list()
put <- function(data, item, g1, g2, quantity, value) {
  rows[[length(rows) + 1]] <<- c(data, item, g1, g2, quantity, sprintf("%.17g", value))
}
run_data <- function(name, d) {
  conditions <- unique(d$condition)   # the questionnaire's order
  for (item in items) {
    keep <- !is.na(d[[item]])
    y <- d[[item]][keep]
    g <- factor(d$condition[keep], levels = conditions)
    k <- kruskal.test(y ~ g)
    all <- paste(conditions, collapse = ", ")
    put(name, item, all, "", "H", k$statistic)
    put(name, item, all, "", "df", k$parameter)
    put(name, item, all, "", "p", k$p.value)
    put(name, item, all, "", "epsilon2", rank_epsilon_squared(y, g, ci = NULL)$rank_epsilon_squared)
    # Every pair: Mann-Whitney with Holm over the item's pairs (pairwise.wilcox.test), Welch t with Holm.
    pw <- suppressWarnings(pairwise.wilcox.test(y, g, p.adjust.method = "holm"))$p.value
    pairs <- combn(conditions, 2)
    raw_t <- c()
    for (j in seq_len(ncol(pairs))) {
      a <- pairs[1, j]; b <- pairs[2, j]
      x1 <- y[g == a]; x2 <- y[g == b]
      w <- suppressWarnings(wilcox.test(x1, x2))
      put(name, item, a, b, "W", w$statistic)
      put(name, item, a, b, "p_mw", w$p.value)
      # pairwise.wilcox.test's matrix: rows are the later levels, columns the earlier ones.
      put(name, item, a, b, "p_mw_holm", pw[b, a])
      t <- t.test(x1, x2)
      put(name, item, a, b, "t", t$statistic)
      put(name, item, a, b, "df_t", t$parameter)
      raw_t <- c(raw_t, t$p.value)
    }
    adj_t <- p.adjust(raw_t, "holm")
    for (j in seq_len(ncol(pairs))) put(name, item, pairs[1, j], pairs[2, j], "p_t_holm", adj_t[j])
  }
}

# Participants P001... in the conditions' order; each answer a rounded normal draw clipped to 1-7
# around the condition's centre (shifted per item); sd `spread` (small: many ties); `miss` empty.
generate <- function(name, conditions, sizes, centre, spread, miss) {
  d <- data.frame(participant = sprintf("P%03d", seq_len(sum(sizes))),
                  condition = rep(conditions, sizes), stringsAsFactors = FALSE)
  for (i in seq_along(items)) {
    mu <- centre[match(d$condition, conditions)] + (i - 2.5) * 0.4
    y <- pmin(7, pmax(1, round(rnorm(nrow(d), mu, spread))))
    y[runif(nrow(d)) < miss] <- NA
    d[[items[i]]] <- y
  }
  out <- d
  for (it in items) out[[it]] <- ifelse(is.na(d[[it]]), "", d[[it]])
  dir.create("tests/golden/likert/data", showWarnings = FALSE)
  write.csv(out, file.path("tests/golden/likert/data", paste0("conditions_", name, ".csv")), row.names = FALSE,
            quote = FALSE)
  d
}

run_data("three", read.csv("tests/data/likert/three_conditions.csv", na.strings = "", stringsAsFactors = FALSE))
set.seed(20260403)
c3 <- c("adaptive", "random", "fixed-block")
run_data("balanced", generate("balanced", c3, c(10, 10, 10), c(4.5, 4, 5), 1.3, 0))
run_data("unbalanced_missing", generate("unbalanced_missing", c3, c(6, 14, 9), c(4, 4.5, 4.2), 1.5, 0.1))
run_data("ties", generate("ties", c(c3, "mirror"), c(7, 12, 5, 9), c(4, 4.2, 3.8, 4.5), 0.6, 0.05))
run_data("small", generate("small", c(c3, "mirror", "none"), c(4, 5, 3, 6, 4), c(3, 4, 5, 4, 6), 1.4, 0))
run_data("large", generate("large", c3, c(30, 25, 35), c(3.8, 4.4, 5.2), 1.4, 0.03))

out <- as.data.frame(do.call(rbind, rows), stringsAsFactors = FALSE)
names(out) <- c("data", "item", "group1", "group2", "quantity", "value")
write.csv(out, "tests/golden/likert/likert_conditions_golden.csv", row.names = FALSE, quote = TRUE)
cat(sprintf("wrote %d golden values on %d data sets\n", nrow(out), length(unique(out$data))))
