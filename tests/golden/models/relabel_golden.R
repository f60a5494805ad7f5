# Golden values of models::relabel_condition_tests (tests/models/test_model_relabelling.cpp,
# docs/findings.md "Mixed models: relabelling p-values"): the worked example's 3 + 3 participants
# x 4 iterations, every one of the C(6, 3) = 20 labellings refitted with lme4/lmerTest.
#   Rscript tests/golden/models/relabel_golden.R > tests/golden/models/relabel_golden.csv
suppressPackageStartupMessages({ library(lme4); library(lmerTest) })
y <- c(0.52, 0.61, 0.58, 0.70,   # A1
       0.45, 0.49, 0.60, 0.66,   # A2
       0.58, 0.63, 0.71, 0.69,   # A3
       0.50, 0.47, 0.52, 0.49,   # R1
       0.41, 0.48, 0.44, 0.50,   # R2
       0.55, 0.51, 0.58, 0.54)   # R3
people <- c("A1", "A2", "A3", "R1", "R2", "R3")
d <- data.frame(participant = rep(people, each = 4), iteration = rep(1:4, 6), y = y)
stats_of <- function(in_random) {
  d$condition <- factor(ifelse(d$participant %in% people[in_random], "random", "adaptive"),
                        levels = c("adaptive", "random"))
  f <- lmer(y ~ condition * factor(iteration) + (1 | participant), data = d, REML = TRUE)
  a <- anova(f)  # type III, Satterthwaite
  t <- lmer(y ~ condition * iteration + (1 | participant), data = d, REML = TRUE)
  ct <- summary(t)$coefficients["conditionrandom:iteration", ]
  c(interaction_f = a["condition:factor(iteration)", "F value"],
    condition_f = a["condition", "F value"],
    interaction_p = a["condition:factor(iteration)", "Pr(>F)"],
    condition_p = a["condition", "Pr(>F)"],
    slope_t = ct[["t value"]], slope_p = ct[["Pr(>|t|)"]])
}
obs <- suppressMessages(stats_of(4:6))
all <- t(suppressMessages(sapply(combn(6, 3, simplify = FALSE), stats_of)))
reach <- function(s, o) mean(s >= o * (1 - 1e-9))
out <- data.frame(
  quantity = c("interaction_f", "condition_f", "slope_t", "interaction_p_model", "condition_p_model",
               "slope_p_model", "p_interaction", "p_condition", "p_slope_difference"),
  value = c(obs[["interaction_f"]], obs[["condition_f"]], obs[["slope_t"]], obs[["interaction_p"]],
            obs[["condition_p"]], obs[["slope_p"]],
            reach(all[, "interaction_f"], obs[["interaction_f"]]),
            reach(all[, "condition_f"], obs[["condition_f"]]),
            reach(abs(all[, "slope_t"]), abs(obs[["slope_t"]]))))
write.csv(out, stdout(), row.names = FALSE, quote = FALSE)
