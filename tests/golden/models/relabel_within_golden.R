# Golden values of models::relabel_condition_tests with the conditions WITHIN participants
# (options.within; tests/models/test_model_relabelling_within_golden.cpp): every labelling, each
# participant's own conditions permuted among themselves (all trials of a condition move together;
# two conditions: a swap or not per participant, 2^P labellings; three: (3!)^P), refitted by
# lme4/lmerTest:
#   factor model  y ~ condition * factor(iteration) + (1 | participant): type-III F (Satterthwaite) of
#                 condition:iteration and condition;
#   trend model   y ~ condition * iteration + (1 | participant): t of each condition<k>:iteration.
# p = the share of labellings whose |statistic| reaches the observed one (>= obs (1 - 1e-6): the
# mirror labellings tie to R's optimiser precision); a labelling that empties a condition x
# iteration cell reaches every statistic (not_computable). REML, bobyqa at rhoend 1e-12 (which warns
# 'a trust region step failed' on a few labellings' near-singular fits, none near an observed value).
#   cd tests/golden/models && Rscript relabel_within_golden.R
# Writes relabel_within_data.csv (dataset, participant, condition, iteration, y) and
# relabel_within_golden.csv (dataset, quantity, value; %.17g). Data sets (conditions a, b[, c]):
#   w2_complete   5 participants x 2 conditions x 3 iterations (32 labellings)
#   w2_missing    6 participants x 2 x 4, 12 % of the trials missing (64)
#   w2_ar_shift   7 participants x 2 x 3, AR(1) trials over the session, b shifted by 0.4 (128)
#   w3_complete   3 participants x 3 conditions x 3 iterations (216)
#   w3_missing    3 participants x 3 x 4, 3 trials missing (216)
suppressPackageStartupMessages({ library(lme4); library(lmerTest) })
ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e6), calc.derivs = FALSE)
set.seed(20261130)
make_set <- function(ds, people, k, iters, ar = 0, shift = 0, missing = 0) {
  rows <- list()
  for (p in seq_len(people)) {
    u <- rnorm(1, 0, 0.3); e <- rnorm(1, 0, 0.5)
    for (b in seq_len(k)) {
      g <- (b + p - 2) %% k + 1  # the blocks in a rotated order
      for (j in seq_len(iters)) {
        e <- ar * e + sqrt(1 - ar^2) * rnorm(1, 0, 0.5)
        rows[[length(rows) + 1]] <- data.frame(dataset = ds, participant = sprintf("P%d", p), condition = letters[g],
                                               iteration = j, y = round(2 + 0.1 * j + u + e + (g == 2) * shift, 6))
      }
    }
  }
  d <- do.call(rbind, rows)
  if (missing > 0) d <- d[-sample(nrow(d), missing), ]
  d
}
sets <- list(make_set("w2_complete", 5, 2, 3), make_set("w2_missing", 6, 2, 4, missing = 6),
             make_set("w2_ar_shift", 7, 2, 3, ar = 0.6, shift = 0.4), make_set("w3_complete", 3, 3, 3),
             make_set("w3_missing", 3, 3, 4, missing = 3))
write.csv(do.call(rbind, sets), "relabel_within_data.csv", row.names = FALSE, quote = FALSE)

stats_of <- function(d, lv) {
  d$condition <- factor(d$condition, levels = lv)
  if (any(table(d$condition, d$iteration) == 0)) return(NULL)
  f <- suppressMessages(lmer(y ~ condition * factor(iteration) + (1 | participant), data = d, control = ctrl))
  a <- anova(f, type = 3)
  t <- suppressMessages(lmer(y ~ condition * iteration + (1 | participant), data = d, control = ctrl))
  ct <- summary(t)$coefficients
  c(a["condition:factor(iteration)", "F value"], a["condition", "F value"],
    ct[paste0("condition", lv[-1], ":iteration"), "t value"])
}
perms3 <- list(c(1, 2, 3), c(1, 3, 2), c(2, 1, 3), c(2, 3, 1), c(3, 1, 2), c(3, 2, 1))
out <- list()
put <- function(ds, q, v) out[[length(out) + 1]] <<- data.frame(dataset = ds, quantity = q, value = sprintf("%.17g", v))
for (d in sets) {
  ds <- d$dataset[1]; lv <- sort(unique(d$condition)); k <- length(lv)
  people <- unique(d$participant); P <- length(people)
  obs <- stats_of(d, lv)
  n <- if (k == 2) 2^P else 6^P
  reach <- numeric(length(obs)); bad <- 0
  for (b in 0:(n - 1)) {
    e <- d
    for (i in seq_len(P)) {
      perm <- if (k == 2) { if (bitwAnd(b, 2^(i - 1)) > 0) c(2, 1) else c(1, 2) } else perms3[[(b %/% 6^(i - 1)) %% 6 + 1]]
      w <- e$participant == people[i]
      e$condition[w] <- lv[perm[match(d$condition[w], lv)]]
    }
    s <- stats_of(e, lv)
    if (is.null(s)) { reach <- reach + 1; bad <- bad + 1; next }
    reach <- reach + (abs(s) >= abs(obs) * (1 - 1e-6))
  }
  put(ds, "labellings", n); put(ds, "not_computable", bad)
  put(ds, "interaction_f", obs[1]); put(ds, "condition_f", obs[2])
  for (j in seq_len(k - 1)) put(ds, paste0("slope_t_", lv[j + 1]), obs[2 + j])
  put(ds, "p_interaction", reach[1] / n); put(ds, "p_condition", reach[2] / n)
  for (j in seq_len(k - 1)) put(ds, paste0("p_slope_", lv[j + 1]), reach[2 + j] / n)
}
write.csv(do.call(rbind, out), "relabel_within_golden.csv", row.names = FALSE, quote = FALSE)
