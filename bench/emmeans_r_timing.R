# What `feint anova|model SCORES --emmeans --contrasts pairwise` computes, in R, in one session:
#   anova: afex::aov_ez (type III, GG) + emmeans on it (multivariate model): cell, condition and
#          iteration means, pairwise ~ condition and pairwise ~ iteration with Tukey;
#   model: lme4::lmer + lmerTest::anova (Satterthwaite) + the condition contrast at each iteration
#          + the same emmeans means and Tukey contrasts (lmer.df = "satterthwaite").
# For the metrics error and confusion (feint's default), as feint. Used by
# bench/run_emmeans_bench.sh; R is needed only here, never by feint or its tests.
#
#   Rscript bench/emmeans_r_timing.R SCORES [REPS]
# Prints "load <user s>" (R's start-up and loading the packages: proc.time() is the process's own
# CPU time), then "anova <median user s> <median elapsed s> <first user s>" and "model ..."
# (median of REPS warm runs, default 5, and the first run in the session, which compiles and
# caches). In session = the median; a one-off Rscript call costs load + first.
suppressPackageStartupMessages({
  library(afex); library(emmeans); library(lme4); library(lmerTest); library(pbkrtest)
})
afex_options(emmeans_model = "multivariate")
emm_options(lmer.df = "satterthwaite", lmerTest.limit = 1e6, pbkrtest.limit = 1e6)
load_user <- proc.time()[["user.self"]]
args <- commandArgs(TRUE)
reps <- if (length(args) > 1) as.integer(args[2]) else 5L
d <- read.csv(args[1])
d$iteration <- factor(d$iteration)
d$condition <- factor(d$condition)
metrics <- c("error", "confusion")

emm_summaries <- function(obj) {
  for (spec in list(~ condition * iteration, ~ condition, ~ iteration))
    summary(suppressMessages(emmeans(obj, spec)), infer = TRUE)
  for (spec in list(~ condition, ~ iteration))
    summary(contrast(suppressMessages(emmeans(obj, spec)), "pairwise", adjust = "tukey"),
            infer = TRUE)
}

run_anova <- function() {
  for (m in metrics) {
    a <- suppressMessages(suppressWarnings(
      aov_ez("participant", m, d[!is.na(d[[m]]), ], between = "condition", within = "iteration")))
    anova(a)
    emm_summaries(a)
  }
}

run_model <- function() {
  for (m in metrics) {
    f <- as.formula(paste(m, "~ condition * iteration + (1 | participant)"))
    fit <- suppressMessages(lmer(f, d))
    anova(fit)
    summary(contrast(emmeans(fit, ~ condition | iteration), "pairwise", adjust = "none"),
            infer = TRUE)
    emm_summaries(fit)
  }
}

time_median <- function(run) {
  first <- system.time(run())[["user.self"]]  # the first calls compile and cache
  t <- vapply(seq_len(reps), function(i) {
    s <- system.time(run())
    c(s[["user.self"]], s[["elapsed"]])
  }, numeric(2))
  c(apply(t, 1, median), first)
}

cat("load", load_user, "\n")
a <- time_median(run_anova)
m <- time_median(run_model)
cat("anova", a, "\n")
cat("model", m, "\n")
