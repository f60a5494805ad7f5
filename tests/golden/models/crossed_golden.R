# Golden values for feint's mixed model with the strategy as a random effect
# (tests/models/test_crossed_model.cpp):
#
#   cd tests/golden/models && Rscript crossed_golden.R
#
# Writes crossed_data.csv (dataset, participant, condition, iteration, strategy, y) and
# crossed_golden.csv (dataset, model, quantity, name, value). Per data set, two random parts of the
# same fixed effects (REML, treatment coding, levels sorted as factor() sorts them):
#   crossed  y ~ condition * iteration + (1 | participant) + (1 | strategy)
#   nested   y ~ condition * iteration + (1 | participant) + (1 | participant:strategy)
# with iteration as a factor (the trend data set: as a number). Written: summary(m)'s coefficient
# table (Estimate, Std. Error, df, t value, Pr(>|t|); lmerTest's Satterthwaite df), theta, sigma,
# REMLcrit, isSingular, VarCorr, lmerTest::ranova's test of the strategy term, and two contrasts
# by lmerTest::contest(joint = FALSE, confint = TRUE): random - adaptive at the last iteration
# ("last") and averaged over the iterations ("mean"; the trend: at iteration 10).
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, Matrix 1.5-3 (Debian 12).
# Optimiser: lme4's bobyqa with rhoend 1e-12 and a large maxfun. The REML criterion is flat to
# rounding near the optimum, so R still stops up to ~1e-7 in theta from the root of the exact
# gradient, and not always at the same point: one of four runs of this script ended elsewhere and
# moved the trend model's intercept df by 1e-6 relative (docs/crossed-random-effects.md); the
# committed goldens are those of the other three.
suppressPackageStartupMessages({ library(lme4); library(lmerTest) })
ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e6),
                    calc.derivs = FALSE)
out <- list()
put <- function(ds, model, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(dataset = ds, model = model, quantity = quantity,
                                        name = name, value = sprintf("%.17g", value))
strategies <- c("ambiguous", "exaggerating", "optimal", "switching")

# n_a + n_b participants (adaptive, random) x `iters`; each trial's strategy drawn with `weights`
# in the adaptive condition and uniformly in the random one. Random parts: participant
# (participant_sd), strategy (strategy_sd), participant x strategy (ps_sd); residual sd 0.1.
make_crossed <- function(ds, seed, n_a, n_b, iters = 1:20, participant_sd = 0.12,
                         strategy_sd = 0.06, ps_sd = 0, missing = 0, weights = rep(1, 4)) {
  set.seed(seed)
  n <- n_a + n_b
  ids <- sprintf("P%02d", seq_len(n))
  cond <- rep(c("adaptive", "random"), c(n_a, n_b))
  d <- expand.grid(iteration = iters, k = seq_len(n))
  d$participant <- ids[d$k]
  d$condition <- cond[d$k]
  adaptive <- d$condition == "adaptive"
  d$strategy <- character(nrow(d))
  d$strategy[adaptive] <- sample(strategies, sum(adaptive), replace = TRUE, prob = weights)
  d$strategy[!adaptive] <- sample(strategies, sum(!adaptive), replace = TRUE)
  u <- rnorm(n, 0, participant_sd)
  s <- setNames(rnorm(4, 0, strategy_sd), strategies)
  ps <- matrix(rnorm(n * 4, 0, ps_sd), n, 4, dimnames = list(ids, strategies))
  eff <- ifelse(adaptive, 0.02, -0.01 * (d$iteration - 1) / length(iters) * 4)
  d$y <- round(0.5 + eff + u[d$k] + s[d$strategy] + ps[cbind(d$participant, d$strategy)] +
               rnorm(nrow(d), 0, 0.1), 6)
  if (missing > 0) d <- d[-sample(nrow(d), round(missing * nrow(d))), ]
  d <- d[order(d$participant, d$iteration), ]
  data.frame(dataset = ds, participant = d$participant, condition = d$condition,
             iteration = d$iteration, strategy = d$strategy, y = d$y)
}

fit_rows <- function(ds, model, m) {
  cf <- coef(summary(m))
  for (nm in rownames(cf)) {
    put(ds, model, "beta", nm, cf[nm, "Estimate"]); put(ds, model, "se", nm, cf[nm, "Std. Error"])
    put(ds, model, "df", nm, cf[nm, "df"]); put(ds, model, "t", nm, cf[nm, "t value"])
    put(ds, model, "p", nm, cf[nm, "Pr(>|t|)"])
  }
  th <- getME(m, "theta"); for (i in seq_along(th)) put(ds, model, "theta", names(th)[i], th[i])
  put(ds, model, "sigma", "", sigma(m)); put(ds, model, "REMLcrit", "", REMLcrit(m))
  put(ds, model, "singular", "", as.numeric(isSingular(m)))
  vc <- as.data.frame(VarCorr(m))
  for (i in seq_len(nrow(vc))) put(ds, model, "variance", vc$grp[i], vc$vcov[i])
  r <- ranova(m)
  row <- grep("strategy", rownames(r))
  put(ds, model, "ranova.LRT", "", r$LRT[row]); put(ds, model, "ranova.p", "", r[["Pr(>Chisq)"]][row])
}

contrast_rows <- function(ds, model, m, d, trend) {
  b <- fixef(m)
  L <- matrix(0, 2, length(b), dimnames = list(c("last", "mean"), names(b)))
  L[, "conditionrandom"] <- 1
  if (trend) {
    L["last", "conditionrandom:iteration"] <- max(d$iteration)
    L["mean", "conditionrandom:iteration"] <- 10
  } else {
    its <- sort(unique(d$iteration))
    L["last", paste0("conditionrandom:iteration", max(its))] <- 1
    L["mean", paste0("conditionrandom:iteration", its[-1])] <- 1 / length(its)
  }
  s <- contest(m, L, joint = FALSE, confint = TRUE)
  for (i in seq_len(nrow(L))) {
    n <- rownames(L)[i]
    put(ds, model, "c.estimate", n, s$Estimate[i]); put(ds, model, "c.SE", n, s[["Std. Error"]][i])
    put(ds, model, "c.df", n, s$df[i]); put(ds, model, "c.t", n, s[["t value"]][i])
    put(ds, model, "c.p", n, s[["Pr(>|t|)"]][i])
    put(ds, model, "c.lower", n, s$lower[i]); put(ds, model, "c.upper", n, s$upper[i])
  }
}

fit_all <- function(d, trend = FALSE) {
  ds <- d$dataset[1]
  d$condition <- factor(d$condition); d$strategy <- factor(d$strategy)
  df <- d
  if (!trend) df$iteration <- factor(df$iteration)
  models <- list(
    crossed = lmer(y ~ condition * iteration + (1 | participant) + (1 | strategy), df,
                   REML = TRUE, control = ctrl),
    nested = lmer(y ~ condition * iteration + (1 | participant) + (1 | participant:strategy), df,
                  REML = TRUE, control = ctrl))
  for (model in names(models)) {
    fit_rows(ds, model, models[[model]])
    contrast_rows(ds, model, models[[model]], d, trend)
  }
}

sets <- list(
  make_crossed("balanced", 41, 15, 15),
  make_crossed("unbalanced_missing", 42, 11, 19, missing = 0.08),
  # Adaptive favours two strategies: strategy is partly confounded with condition; a
  # participant x strategy variance in the simulation.
  make_crossed("adaptive_choice", 43, 16, 14, ps_sd = 0.05, missing = 0.03,
               weights = c(0.1, 0.6, 0.25, 0.05)),
  make_crossed("nested_strong", 44, 14, 16, strategy_sd = 0.02, ps_sd = 0.08, missing = 0.05),
  # No strategy variance in the simulation: lme4 puts its theta on the boundary (isSingular).
  make_crossed("singular_strategy", 46, 15, 15, strategy_sd = 0, missing = 0.05),
  make_crossed("trend", 47, 17, 13, missing = 0.06))
for (d in sets) fit_all(d, trend = d$dataset[1] == "trend")
write.csv(do.call(rbind, sets), "crossed_data.csv", row.names = FALSE, quote = FALSE)
write.csv(do.call(rbind, out), "crossed_golden.csv", row.names = FALSE, quote = FALSE)
