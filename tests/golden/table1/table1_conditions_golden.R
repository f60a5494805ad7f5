# Golden values of Table 1's comparison of three or more conditions (feint/tables/table1_conditions.hpp).
# R 4.2 with afex and effectsize. Run from the repository root:
#   Rscript tests/golden/table1/table1_conditions_golden.R
# Writes, into tests/golden/table1/:
#  - the scores files (participant, condition, iteration, error, confusion; an empty cell = missing):
#      b3_balanced.csv    between, 3 conditions x 8 participants, 6 iterations
#      b4_unbalanced.csv  between, 4 conditions of 5, 9, 6, 7 participants, unequal variances
#      b3_missing.csv     between, 3 conditions of 7, 10, 6, empty cells and absent rows
#      b4_ties.csv        between, 4 conditions of 6, 6, 8, 5, values on a 0.1 grid (ties), empty cells
#      w3_within.csv      within, 3 conditions, 11 participants; one absent row, one empty cell
#      w4_within.csv      within, 4 conditions, 9 participants, complete
#      tiny_between.csv   between, 3 conditions of 2, 2, 3 (210 labellings), one empty cell
#      tiny_within.csv    within, 3 conditions, 4 participants ((3!)^4 = 1296 labellings)
#      w3_strong.csv      within, 3 conditions far apart, 12 participants, 3 iterations, complete
#      w4_missing.csv     within, 4 conditions, 10 participants, 4 iterations; absent rows, empty cells
#  - table1_conditions_golden.csv: dataset, metric, iteration, quantity, value (%.17g; NA = none).
# Between, per metric and iteration: oneway.test(y ~ g) (Welch, var.equal = FALSE) and its Holm
# adjustment over the iterations; oneway.test(var.equal = TRUE) = summary(aov(y ~ g)) with
# effectsize's eta_squared / omega_squared and their one-sided 95 % intervals (the effectsize bound,
# and the exact bound: the root of pf(F*, df1, df2, ncp) = 0.95 by uniroot(tol = 1e-15), F* the
# pseudo-F of the estimate, as effectsize's .F_to_pve converts it); kruskal.test and
# effectsize::rank_epsilon_squared. Within: afex::aov_ez(within = "condition") on the participants
# with every condition at that iteration, Greenhouse-Geisser corrected (anova(correction = "GG")),
# its ges with effectsize's eta_squared(generalized = TRUE) interval (and the exact bound of that
# definition, as above) and the GG epsilon; friedman.test(y ~ condition | participant) with Kendall's W.
# Tiny sets: the step-down maxF p (Westfall & Young) by complete enumeration of the relabellings,
# each statistic from oneway.test (between) or from the one-way repeated-measures F (within).
options(warn = 1)
suppressMessages({
  library(afex)
  library(effectsize)
})
dir <- "tests/golden/table1"
g17 <- function(x) ifelse(is.na(x), "NA", sprintf("%.17g", x))

# ---- the data sets -------------------------------------------------------------------------------

between_data <- function(sizes, conditions, iterations, shift, sd, grid = 1e-4) {
  rows <- list()
  p <- 0
  for (c in seq_along(sizes)) for (i in seq_len(sizes[c])) {
    p <- p + 1
    for (it in seq_len(iterations)) {
      rows[[length(rows) + 1]] <- data.frame(
        participant = sprintf("P%02d", p), condition = conditions[c], iteration = it,
        error = round(rnorm(1, 0.5 + shift[c], sd[c]) / grid) * grid,
        confusion = round(rnorm(1, 0.85 - shift[c], 1.5 * sd[c]) / grid) * grid)
    }
  }
  do.call(rbind, rows)
}

within_data <- function(n, conditions, iterations, shift, sd) {
  rows <- list()
  for (p in seq_len(n)) {
    person <- rnorm(1, 0, 0.05)
    for (c in seq_along(conditions)) for (it in seq_len(iterations)) {
      rows[[length(rows) + 1]] <- data.frame(
        participant = sprintf("P%02d", p), condition = conditions[c], iteration = it,
        error = round(0.5 + person + shift[c] + rnorm(1, 0, sd[c]), 4),
        confusion = round(0.85 - 2 * person - shift[c] + rnorm(1, 0, 1.5 * sd[c]), 4))
    }
  }
  do.call(rbind, rows)
}

write_scores <- function(d, name) {
  write.csv(d, file.path(dir, name), row.names = FALSE, quote = FALSE, na = "")
}

set.seed(20260501)
three <- c("adaptive", "random", "fixed-block")
four <- c("adaptive", "random", "fixed-block", "honest")
write_scores(between_data(c(8, 8, 8), three, 6, c(0, 0.04, -0.03), c(0.08, 0.08, 0.08)), "b3_balanced.csv")
write_scores(between_data(c(5, 9, 6, 7), four, 5, c(0, 0.05, 0.02, -0.04), c(0.05, 0.12, 0.08, 0.2)),
             "b4_unbalanced.csv")
d <- between_data(c(7, 10, 6), three, 8, c(0.02, 0, -0.05), c(0.1, 0.06, 0.09))
d$error[c(3, 17, 40, 77, 101)] <- NA
d$confusion[c(5, 17, 58, 130)] <- NA
d <- d[-c(12, 66, 150), ]  # trials that were never recorded
write_scores(d, "b3_missing.csv")
d <- between_data(c(6, 6, 8, 5), four, 4, c(0, 0.1, 0.05, -0.05), c(0.15, 0.2, 0.15, 0.25), grid = 0.1)
d$error[c(7, 30)] <- NA
d$confusion[c(2, 51, 88)] <- NA
write_scores(d, "b4_ties.csv")
d <- within_data(11, three, 5, c(0, 0.03, -0.02), c(0.05, 0.09, 0.07))
d$error[d$participant == "P04" & d$condition == "random" & d$iteration == 2] <- NA
d <- d[!(d$participant == "P07" & d$condition == "fixed-block" & d$iteration == 4), ]
write_scores(d, "w3_within.csv")
write_scores(within_data(9, four, 4, c(0, 0.05, -0.03, 0.02), c(0.06, 0.04, 0.1, 0.07)), "w4_within.csv")
d <- between_data(c(2, 2, 3), three, 3, c(0, 0.1, -0.1), c(0.05, 0.1, 0.08))
d$confusion[4] <- NA
write_scores(d, "tiny_between.csv")
write_scores(within_data(4, three, 2, c(0, 0.06, -0.04), c(0.04, 0.06, 0.05)), "tiny_within.csv")
# Drawn last so that the sets above keep their draws: conditions far apart, so that ges's lower
# bounds are above 0.
write_scores(within_data(12, three, 3, c(0, 0.08, -0.06), c(0.04, 0.05, 0.04)), "w3_strong.csv")
# Within, 4 conditions, with absent trials and empty cells in several participants (each
# iteration's tests keep the participants with every condition there).
d <- within_data(10, four, 4, c(0, 0.06, -0.04, 0.03), c(0.05, 0.07, 0.06, 0.08))
d$error[c(5, 38, 77, 121)] <- NA
d$confusion[c(12, 38, 140)] <- NA
d <- d[-c(20, 64, 99), ]  # trials that were never recorded
write_scores(d, "w4_missing.csv")

# ---- the statistics ------------------------------------------------------------------------------

out <- data.frame(dataset = character(), metric = character(), iteration = integer(),
                  quantity = character(), value = character(), stringsAsFactors = FALSE)
put <- function(dataset, metric, iteration, quantity, value) {
  out[nrow(out) + 1, ] <<- list(dataset, metric, iteration, quantity, g17(unname(value)))
}

# The exact lower bound of a one-sided 95 % interval of eta2-type effect sizes: effectsize's own
# comes from an optim() search (docs/effect-sizes.md says how far off it is).
exact_low <- function(es, df1, df2, level = 0.95) {
  f <- max(0, (es / df1) / ((1 - es) / df2))
  if (f <= qf(level, df1, df2)) return(0)
  h <- function(ncp) pf(f, df1, df2, ncp) - level
  hi <- max(10, 2 * f * df1)
  while (h(hi) > 0) hi <- hi * 2
  ncp <- uniroot(h, c(0, hi), tol = 1e-15)$root
  ncp / (ncp + df2)
}

read_scores <- function(name) {
  d <- read.csv(file.path(dir, name), na.strings = "", stringsAsFactors = FALSE)
  d$condition <- factor(d$condition, levels = unique(d$condition))
  d
}

between_golden <- function(name) {
  d <- read_scores(name)
  for (metric in c("error", "confusion")) {
    welch_p <- c()
    for (it in sort(unique(d$iteration))) {
      x <- d[d$iteration == it & !is.na(d[[metric]]), ]
      y <- x[[metric]]
      g <- droplevels(x$condition)
      # A condition with one value: R stops ("not enough observations"); feint: not computable.
      w <- tryCatch(oneway.test(y ~ g), error = function(e) list(statistic = NA, parameter = c(NA, NA),
                                                                 p.value = NA))
      put(name, metric, it, "welch_F", w$statistic)
      put(name, metric, it, "welch_df1", w$parameter[1])
      put(name, metric, it, "welch_df2", w$parameter[2])
      put(name, metric, it, "welch_p", w$p.value)
      welch_p <- c(welch_p, w$p.value)
      m <- aov(y ~ g)
      s <- summary(m)[[1]]
      put(name, metric, it, "aov_F", s$`F value`[1])
      put(name, metric, it, "aov_df1", s$Df[1])
      put(name, metric, it, "aov_df2", s$Df[2])
      put(name, metric, it, "aov_p", s$`Pr(>F)`[1])
      e <- eta_squared(m, partial = FALSE, ci = 0.95, verbose = FALSE)
      put(name, metric, it, "eta2", e$Eta2)
      put(name, metric, it, "eta2_low_effectsize", e$CI_low)
      put(name, metric, it, "eta2_low", exact_low(e$Eta2, s$Df[1], s$Df[2]))
      o <- omega_squared(m, partial = FALSE, ci = 0.95, verbose = FALSE)
      put(name, metric, it, "omega2", o$Omega2)
      put(name, metric, it, "omega2_low_effectsize", o$CI_low)
      put(name, metric, it, "omega2_low", exact_low(o$Omega2, s$Df[1], s$Df[2]))
      k <- kruskal.test(y ~ g)
      put(name, metric, it, "kw_chi2", k$statistic)
      put(name, metric, it, "kw_df", k$parameter)
      put(name, metric, it, "kw_p", k$p.value)
      put(name, metric, it, "kw_epsilon2", rank_epsilon_squared(y ~ g, ci = NULL)$rank_epsilon_squared)
    }
    its <- sort(unique(d$iteration))
    holm <- p.adjust(welch_p, "holm")
    for (i in seq_along(its)) put(name, metric, its[i], "welch_p_holm", holm[i])
  }
}

# The participants with every condition at one iteration, as a participant x condition matrix.
complete_matrix <- function(x, metric) {
  w <- reshape(x[, c("participant", "condition", metric)], idvar = "participant", timevar = "condition",
               direction = "wide")
  m <- as.matrix(w[, -1, drop = FALSE])
  rownames(m) <- w$participant
  m[complete.cases(m), , drop = FALSE]
}

within_golden <- function(name) {
  d <- read_scores(name)
  for (metric in c("error", "confusion")) {
    rm_p <- c()
    for (it in sort(unique(d$iteration))) {
      x <- d[d$iteration == it, ]
      m <- complete_matrix(x, metric)
      long <- data.frame(participant = rep(rownames(m), ncol(m)),
                         condition = factor(rep(levels(d$condition), each = nrow(m)), levels = levels(d$condition)),
                         y = as.vector(m))
      a <- suppressWarnings(suppressMessages(aov_ez("participant", "y", long, within = "condition")))
      gg <- anova(a, correction = "GG")
      put(name, metric, it, "rm_F", gg$F[1])
      put(name, metric, it, "rm_df1", gg$`num Df`[1])
      put(name, metric, it, "rm_df2", gg$`den Df`[1])
      put(name, metric, it, "rm_p", gg$`Pr(>F)`[1])
      put(name, metric, it, "rm_ges", gg$ges[1])
      # ges's interval as effectsize gives it on the afex model (df uncorrected for sphericity),
      # and the exact root of that definition.
      es <- eta_squared(a, generalized = TRUE, ci = 0.95, verbose = FALSE)
      put(name, metric, it, "rm_ges_low_effectsize", es$CI_low[1])
      put(name, metric, it, "rm_ges_high_effectsize", es$CI_high[1])
      put(name, metric, it, "rm_ges_low", exact_low(gg$ges[1], ncol(m) - 1, (ncol(m) - 1) * (nrow(m) - 1)))
      put(name, metric, it, "rm_gg_eps", summary(a)$pval.adjustments[1, "GG eps"])
      put(name, metric, it, "rm_n", nrow(m))
      rm_p <- c(rm_p, gg$`Pr(>F)`[1])
      f <- friedman.test(m)
      put(name, metric, it, "friedman_chi2", f$statistic)
      put(name, metric, it, "friedman_df", f$parameter)
      put(name, metric, it, "friedman_p", f$p.value)
      put(name, metric, it, "kendalls_w", f$statistic / (nrow(m) * (ncol(m) - 1)))
    }
    its <- sort(unique(d$iteration))
    holm <- p.adjust(rm_p, "holm")
    for (i in seq_along(its)) put(name, metric, its[i], "rm_p_holm", holm[i])
  }
}

# ---- the maxF family by complete enumeration ------------------------------------------------------

# Step-down maxF p-values (Westfall & Young 1993, Algorithm 2.8) from the observed statistics and
# one row of statistics per labelling (the observed labelling among them); NA = not computable.
step_down <- function(obs, all) {
  ok <- which(is.finite(obs))
  ord <- ok[order(-obs[ok])]
  reach <- numeric(length(ord))
  for (b in seq_len(nrow(all))) {
    s <- all[b, ]
    s[!is.finite(s)] <- -Inf
    u <- -Inf
    for (r in rev(seq_along(ord))) {
      j <- ord[r]
      u <- max(u, s[j])
      if (u >= obs[j] - 1e-9 * max(1, abs(obs[j]))) reach[r] <- reach[r] + 1
    }
  }
  p <- rep(NA_real_, length(obs))
  p[ord] <- cummax(reach / nrow(all))
  p
}

# Every distinct assignment of the labels (a multiset permutation), as rows.
multiset_permutations <- function(labels) {
  if (length(labels) <= 1) return(matrix(labels, nrow = 1))
  out <- NULL
  for (v in unique(labels)) {
    rest <- labels[-match(v, labels)]
    out <- rbind(out, cbind(v, multiset_permutations(rest)))
  }
  unname(out)
}

tiny_between_golden <- function(name) {
  d <- read_scores(name)
  people <- unique(d$participant)
  group <- as.character(d$condition[match(people, d$participant)])
  its <- sort(unique(d$iteration))
  for (metric in c("error", "confusion")) {
    y <- sapply(its, function(it) d[[metric]][d$iteration == it][match(people, d$participant[d$iteration == it])])
    welch <- function(g) sapply(seq_along(its), function(j) {
      keep <- !is.na(y[, j])
      tryCatch(unname(oneway.test(y[keep, j] ~ factor(g[keep]))$statistic), error = function(e) NA_real_)
    })
    obs <- welch(group)
    all <- t(apply(multiset_permutations(group), 1, welch))
    p <- step_down(obs, all)
    for (j in seq_along(its)) put(name, metric, its[j], "p_maxf", p[j])
    put(name, metric, NA, "labellings", nrow(all))
  }
}

# The one-way repeated-measures F of a participant x condition matrix (complete rows).
rm_f <- function(m) {
  m <- m[complete.cases(m), , drop = FALSE]
  n <- nrow(m); k <- ncol(m)
  centred <- m - rowMeans(m)
  ss_cond <- n * sum(colMeans(centred)^2)
  ss_error <- sum(centred^2) - ss_cond
  (ss_cond / (k - 1)) / (ss_error / ((k - 1) * (n - 1)))
}

all_orders <- function(k) multiset_permutations(seq_len(k))

tiny_within_golden <- function(name) {
  d <- read_scores(name)
  people <- unique(d$participant)
  conditions <- levels(d$condition)
  its <- sort(unique(d$iteration))
  orders <- all_orders(length(conditions))
  for (metric in c("error", "confusion")) {
    cube <- lapply(its, function(it) {
      x <- d[d$iteration == it, ]
      sapply(conditions, function(c) x[[metric]][x$condition == c][match(people, x$participant[x$condition == c])])
    })
    stats_of <- function(choice) sapply(seq_along(its), function(j) {
      m <- cube[[j]]
      for (i in seq_along(people)) m[i, ] <- cube[[j]][i, orders[choice[i], ]]
      rm_f(m)
    })
    obs <- stats_of(rep(1, length(people)))  # orders[1, ] is the identity
    choices <- as.matrix(expand.grid(rep(list(seq_len(nrow(orders))), length(people))))
    all <- t(apply(choices, 1, stats_of))
    p <- step_down(obs, all)
    for (j in seq_along(its)) put(name, metric, its[j], "p_maxf", p[j])
    put(name, metric, NA, "labellings", nrow(all))
  }
}

for (name in c("b3_balanced.csv", "b4_unbalanced.csv", "b3_missing.csv", "b4_ties.csv", "tiny_between.csv"))
  between_golden(name)
for (name in c("w3_within.csv", "w4_within.csv", "tiny_within.csv", "w3_strong.csv", "w4_missing.csv"))
  within_golden(name)
tiny_between_golden("tiny_between.csv")
tiny_within_golden("tiny_within.csv")
write.csv(out, file.path(dir, "table1_conditions_golden.csv"), row.names = FALSE, quote = FALSE)
