# Golden values of `feint likert` (R 4.2, psych) on six data sets: tests/data/likert/golden_input.csv
# ("input") and five generated here with a fixed seed into tests/golden/likert/data/ (unbalanced
# conditions, missing answers, many ties and answers at the reference, a small and a large study).
# Run from the repository root:  Rscript tests/golden/likert/make_golden.R
# Writes tests/golden/likert/golden.csv: data, run, group, name, quantity, value (%.17g).
#
# Settings mirrored by tests/tables/test_likert_golden.cpp:
#   common : scale 1-7, --reverse boring, --composite enjoyment=entertainment,boring,fun
#   one    : one-sample against the midpoint 4, each condition, --p-adjust holm
#   compare: --compare adaptive,random
#   paper  : --paper (four items against 3.5), --condition adaptive
suppressMessages(library(psych))
items <- c("entertainment", "deception", "intelligence", "trust", "boring", "fun")
comp_items <- c("entertainment", "boring", "fun")
names_all <- c(items, "enjoyment")

rows <- list()
data_name <- ""
put <- function(run, group, name, quantity, value) {
  rows[[length(rows) + 1]] <<- c(data_name, run, group, name, quantity, sprintf("%.17g", value))
}

descriptives <- function(run, group, name, v, composite) {
  x <- v[!is.na(v)]
  put(run, group, name, "n", length(x))
  put(run, group, name, "missing", sum(is.na(v)))
  put(run, group, name, "mean", mean(x))
  put(run, group, name, "sd", sd(x))
  q <- quantile(x, c(0.25, 0.5, 0.75), type = 7)
  put(run, group, name, "q1", q[[1]]); put(run, group, name, "median", q[[2]])
  put(run, group, name, "q3", q[[3]]); put(run, group, name, "iqr", IQR(x))
  put(run, group, name, "pct_below", 100 * mean(x < 4))
  put(run, group, name, "pct_at", 100 * mean(x == 4))
  put(run, group, name, "pct_above", 100 * mean(x > 4))
  if (!composite) {
    counts <- table(factor(x, levels = 1:7))
    for (k in 1:7) put(run, group, name, paste0("count_", k), counts[[k]])
  }
}

signed_rank <- function(run, group, name, x, mu) {
  x <- x[!is.na(x)]
  if (all(x == mu)) return(c(NA, NA))  # every answer at the reference: feint says not computable
  w <- suppressWarnings(wilcox.test(x, mu = mu))
  dz <- x - mu
  nz <- dz[dz != 0]
  n <- length(nz)
  exact <- n < 50 && !any(duplicated(abs(nz))) && !any(dz == 0)
  S <- n * (n + 1) / 2
  put(run, group, name, "V", w$statistic[[1]])
  put(run, group, name, "wilcoxon_p", w$p.value)
  put(run, group, name, "wilcoxon_exact", as.numeric(exact))
  put(run, group, name, "rank_biserial", 2 * w$statistic[[1]] / S - 1)
  tt <- t.test(x, mu = mu)
  put(run, group, name, "t", tt$statistic[[1]])
  put(run, group, name, "t_df", tt$parameter[[1]])
  put(run, group, name, "t_p", tt$p.value)
  put(run, group, name, "cohen_d", (mean(x) - mu) / sd(x))
  c(w$p.value, tt$p.value)
}

alpha_of <- function(run, group, df) {
  a <- suppressWarnings(suppressMessages(psych::alpha(na.omit(df[comp_items]))))
  put(run, group, "enjoyment", "alpha_n", nrow(na.omit(df[comp_items])))
  put(run, group, "enjoyment", "cronbach_alpha", a$total$raw_alpha)
  for (k in seq_along(comp_items)) {
    put(run, group, "enjoyment", paste0("alpha_if_dropped_", comp_items[k]),
        a$alpha.drop$raw_alpha[k])
  }
}

run_data <- function(name, d) {
  data_name <<- name
  d$boring <- 1 + 7 - d$boring                       # reverse coding: x -> min + max - x
  d$enjoyment <- ifelse(complete.cases(d[comp_items]), rowMeans(d[comp_items]), NA)
  # --- one: each condition against the midpoint 4, holm across items and the composite ------
  for (g in unique(d$condition)) {
    s <- d[d$condition == g, ]
    pw <- c(); pt <- c(); nm <- c()
    for (name in names_all) {
      descriptives("one", g, name, s[[name]], name == "enjoyment")
      p <- signed_rank("one", g, name, s[[name]], 4)
      if (is.na(p[1])) next
      pw <- c(pw, p[1]); pt <- c(pt, p[2]); nm <- c(nm, name)
    }
    # The family leaves the not-computable test out (p.adjust's n counts non-NA only).
    aw <- p.adjust(pw, "holm"); at <- p.adjust(pt, "holm")
    for (k in seq_along(nm)) {
      put("one", g, nm[k], "wilcoxon_p_holm", aw[k])
      put("one", g, nm[k], "t_p_holm", at[k])
    }
    alpha_of("one", g, s)
  }
  # --- compare: adaptive (A) against random (B) ---------------------------------------------
  A <- d[d$condition == "adaptive", ]; B <- d[d$condition == "random", ]
  for (name in names_all) {
    x <- A[[name]]; x <- x[!is.na(x)]; y <- B[[name]]; y <- y[!is.na(y)]
    w <- suppressWarnings(wilcox.test(x, y))
    put("compare", "adaptive-random", name, "W", w$statistic[[1]])
    put("compare", "adaptive-random", name, "mw_p", w$p.value)
    put("compare", "adaptive-random", name, "rank_biserial",
        2 * w$statistic[[1]] / (length(x) * length(y)) - 1)
    tt <- t.test(x, y)
    put("compare", "adaptive-random", name, "t", tt$statistic[[1]])
    put("compare", "adaptive-random", name, "t_df", tt$parameter[[1]])
    put("compare", "adaptive-random", name, "t_p", tt$p.value)
    put("compare", "adaptive-random", name, "median_B", median(y))
    put("compare", "adaptive-random", name, "iqr_B", IQR(y))
  }
  alpha_of("compare", "adaptive-random", rbind(A, B))
  # --- paper: the four items against 3.5 in the adaptive condition --------------------------
  for (name in c("entertainment", "deception", "intelligence", "trust")) {
    signed_rank("paper", "adaptive", name, A[[name]], 3.5)
  }
}

# Generated data sets: participants P001... in the conditions' order; each answer is a rounded
# normal draw clipped to 1-7 around the condition's centre for the item (sd `spread`: small
# spreads give many ties and answers at the midpoint); `miss` = probability of an empty answer.
generate <- function(name, sizes, centre, spread, miss) {
  conditions <- c("adaptive", "random", "pilot")
  d <- data.frame(participant = sprintf("P%03d", seq_len(sum(sizes))),
                  condition = rep(conditions, sizes), stringsAsFactors = FALSE)
  for (i in seq_along(items)) {
    mu <- centre[match(d$condition, conditions)] + (i - 3.5) * 0.3
    y <- pmin(7, pmax(1, round(rnorm(nrow(d), mu, spread))))
    y[runif(nrow(d)) < miss] <- NA
    d[[items[i]]] <- y
  }
  out <- d
  for (it in items) out[[it]] <- ifelse(is.na(d[[it]]), "", d[[it]])
  dir.create("tests/golden/likert/data", showWarnings = FALSE)
  write.csv(out, file.path("tests/golden/likert/data", paste0(name, ".csv")), row.names = FALSE, quote = FALSE)
  d
}

run_data("input", read.csv("tests/data/likert/golden_input.csv", na.strings = "", stringsAsFactors = FALSE))
set.seed(20260402)
run_data("balanced", generate("balanced", c(15, 15, 6), c(5, 4, 3.5), 1.4, 0))
run_data("unbalanced_missing", generate("unbalanced_missing", c(9, 22, 4), c(4.5, 3.8, 4.2), 1.6, 0.1))
run_data("ties", generate("ties", c(11, 17, 5), c(4.2, 4, 3.9), 0.7, 0.05))
run_data("large", generate("large", c(45, 38, 10), c(4.8, 4.1, 4), 1.5, 0.04))
run_data("small", generate("small", c(5, 7, 4), c(5.5, 3, 4), 1.5, 0))

out <- as.data.frame(do.call(rbind, rows), stringsAsFactors = FALSE)
names(out) <- c("data", "run", "group", "name", "quantity", "value")
write.csv(out, "tests/golden/likert/golden.csv", row.names = FALSE, quote = FALSE)
cat(sprintf("wrote %d golden values on %d data sets\n", nrow(out), length(unique(out$data))))
