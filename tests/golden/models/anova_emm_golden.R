# Golden values for the estimated marginal means and contrasts of `feint anova`:
# emmeans 1.8.4-1 on afex::aov_ez objects (afex 1.2-1), with emmeans' default for afex objects,
# the multivariate model (afex_options(emmeans_model = "multivariate")): cell means, and every
# contrast's SE from the pooled within-condition covariance of the iterations, df = N - a.
#   cd tests/golden/models && Rscript anova_emm_golden.R
# Reads anova_data.csv (anova_golden.R), writes anova_emm_strong.csv and anova_emm_golden.csv (case,
# quantity, name, value).
suppressPackageStartupMessages({ library(afex); library(emmeans) })
afex_options(emmeans_model = "multivariate")
d0 <- read.csv("anova_data.csv")
out <- list()
put <- function(case, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(case = case, quantity = quantity, name = name,
                                        value = sprintf("%.17g", value))
rows <- function(case, label, obj, means) {
  s <- as.data.frame(summary(obj, infer = c(TRUE, TRUE)))
  by <- intersect(c("condition", "iteration"), names(s))
  for (i in seq_len(nrow(s))) {
    n <- if (means) paste(vapply(by, function(b) as.character(s[[b]][i]), ""), collapse = "|")
         else paste(c(as.character(s$contrast[i]), vapply(by, function(b) as.character(s[[b]][i]), "")), collapse = "|")
    put(case, paste0(label, ".estimate"), n, if (means) s$emmean[i] else s$estimate[i])
    put(case, paste0(label, ".SE"), n, s$SE[i]); put(case, paste0(label, ".df"), n, s$df[i])
    put(case, paste0(label, ".lower"), n, s$lower.CL[i]); put(case, paste0(label, ".upper"), n, s$upper.CL[i])
    if (!means) { put(case, paste0(label, ".t"), n, s$t.ratio[i]); put(case, paste0(label, ".p"), n, s$p.value[i]) }
  }
}
# A strong effect, for p-values far below 1e-6: balanced_spherical with 0.2 * (iteration - 1)
# added to every 'adaptive' value, written to anova_emm_strong.csv (same columns).
s <- d0[d0$case == "balanced_spherical", ]
s$case <- "strong_effect"
s$value <- sprintf("%.6f", s$value + ifelse(s$condition == "adaptive", 0.2 * (s$iteration - 1), 0))
write.csv(s, "anova_emm_strong.csv", row.names = FALSE, quote = FALSE)
s$value <- as.numeric(s$value)
d0 <- rbind(d0, s)
# three_conditions (anova_data.csv: 5, 8, 6 participants, unequal variances) comes last, so that the
# other cases' lines stay as they were; with it the pairs of conditions over the iterations
# (cond_pairs.<adjust>: none, holm, tukey).
for (case in c("balanced_spherical", "unbalanced_nonspherical", "missing_trials", "strong_effect",
               "three_conditions")) {
  d <- d0[d0$case == case & !is.na(d0$value), ]
  d$iteration <- factor(d$iteration)
  a <- suppressMessages(suppressWarnings(aov_ez("participant", "value", d, between = "condition",
                                                 within = "iteration")))
  rows(case, "cells", emmeans(a, ~ condition * iteration), TRUE)
  rows(case, "condition", suppressMessages(emmeans(a, ~ condition)), TRUE)
  rows(case, "iteration", suppressMessages(emmeans(a, ~ iteration)), TRUE)
  rows(case, "cond_by_it", contrast(emmeans(a, ~ condition | iteration), "pairwise"), FALSE)
  for (adj in c("none", "holm", "tukey"))
    rows(case, paste0("it_by_cond.", adj), contrast(emmeans(a, ~ iteration | condition), "pairwise", adjust = adj), FALSE)
  rows(case, "poly_by_cond", contrast(emmeans(a, ~ iteration | condition), "poly"), FALSE)
  if (case == "three_conditions") {
    for (adj in c("none", "holm", "tukey"))
      rows(case, paste0("cond_pairs.", adj), suppressMessages(contrast(emmeans(a, ~ condition), "pairwise", adjust = adj)), FALSE)
    # R's qtukey stops at |dq| < 1e-4 (1e-8 on these bounds with three means): the bounds from the
    # root of R's own ptukey(q, 3, df) = 0.95 (uniroot, tol 1e-14) as well (<label>.lower_exact).
    for (label in c("cond_by_it", "cond_pairs.tukey")) {
      est <- out[vapply(out, function(r) r$case == case && r$quantity == paste0(label, ".estimate"), TRUE)]
      for (r in est) {
        v <- function(q) as.numeric(out[vapply(out, function(o) o$case == case && o$quantity == paste0(label, ".", q) &&
                                                   o$name == r$name, TRUE)][[1]]$value)
        df <- v("df")
        q <- uniroot(function(q) ptukey(q, 3, df) - 0.95, c(1, 10), tol = 1e-14)$root
        put(case, paste0(label, ".lower_exact"), r$name, v("estimate") - q / sqrt(2) * v("SE"))
        put(case, paste0(label, ".upper_exact"), r$name, v("estimate") + q / sqrt(2) * v("SE"))
      }
    }
  }
}
write.csv(do.call(rbind, out), "anova_emm_golden.csv", row.names = FALSE, quote = FALSE)
