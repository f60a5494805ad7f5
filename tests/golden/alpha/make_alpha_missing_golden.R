# Golden values for Cronbach's alpha with missing answers (tests/stats/test_alpha_missing.cpp):
# psych::alpha's default (covariances from pairwise-complete observations, use = "pairwise") and
# complete cases (psych::alpha(na.omit(items))). Regenerate from the repository root with
#   Rscript tests/golden/alpha/make_alpha_missing_golden.R
# Numbers are written with sprintf("%.17g"); items are '|'-separated, answers ';'-separated, NA
# for a missing answer.
suppressPackageStartupMessages(library(psych))
set.seed(20261123)
out_dir <- "tests/golden/alpha"
if (!dir.exists(out_dir)) stop("run from the repository root")

g17 <- function(v) ifelse(is.na(v), "NA", sprintf("%.17g", v))
vec <- function(v) paste(g17(v), collapse = ";")

rows <- list()
add_case <- function(label, items) {
  df <- as.data.frame(items, col.names = paste0("item", seq_along(items)))
  one <- function(m) {
    a <- suppressWarnings(suppressMessages(psych::alpha(m, warnings = FALSE)))
    drop <- a$alpha.drop$raw_alpha[match(names(m), rownames(a$alpha.drop))]
    list(raw = a$total$raw_alpha, drop = drop)
  }
  p <- one(df)              # psych's default: use = "pairwise"
  cc <- one(na.omit(df))    # complete cases
  rows[[length(rows) + 1]] <<- data.frame(
    case = label, items = paste(vapply(items, vec, ""), collapse = "|"),
    pairwise_raw_alpha = g17(p$raw), pairwise_drop = vec(p$drop),
    complete_raw_alpha = g17(cc$raw), complete_drop = vec(cc$drop),
    complete_n = nrow(na.omit(df)))
}
scale_items <- function(n, k, loading = 0.7) {
  f <- rnorm(n)
  lapply(seq_len(k), function(j) {
    v <- loading * f + sqrt(1 - loading^2) * rnorm(n)
    pmin(7, pmax(1, round(4 + 1.5 * v)))
  })
}
punch <- function(items, share) {
  lapply(items, function(v) { v[runif(length(v)) < share] <- NA; v })
}
invisible(capture.output({
  for (k in c(2, 3, 4, 6)) {
    add_case(sprintf("k%d_n40_10pct_missing", k), punch(scale_items(40, k), 0.10))
    add_case(sprintf("k%d_n25_25pct_missing", k), punch(scale_items(25, k), 0.25))
  }
  items <- scale_items(30, 3)
  items[[1]][c(3, 17)] <- NA
  items[[3]][c(17, 25, 29)] <- NA
  add_case("k3_n30_few_missing", items)
  items <- scale_items(12, 4, 0.4)
  items[[2]][1:5] <- NA  # one item answered by few
  add_case("k4_n12_one_sparse_item", items)
  add_case("k5_n80_no_missing", scale_items(80, 5))  # both methods agree
}))
out <- do.call(rbind, rows)
write.csv(out, file.path(out_dir, "alpha_missing.csv"), row.names = FALSE, quote = FALSE)
cat("wrote", nrow(out), "psych::alpha cases with missing answers\n")
