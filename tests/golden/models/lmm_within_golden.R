# Golden values for feint's linear mixed model with the condition WITHIN participants
# (tests/models/test_mixed_model_within_golden.cpp):
#
#   cd tests/golden/models && Rscript lmm_within_golden.R
#
# Writes lmm_within_data.csv (dataset, participant, condition, iteration, y) and
# lmm_within_golden.csv (dataset, model, ddf, quantity, name, value). Per data set, three models
# (REML, treatment coding, levels sorted as factor() sorts them):
#   f_int    y ~ condition * factor(iteration) + (1 | participant)
#   f_slope  y ~ condition * factor(iteration) + (1 + condition | participant)
#   t_slope  y ~ condition * iteration         + (1 + condition | participant)   (linear trend)
# with fixef, diag(vcov), diag(pbkrtest::vcovAdj), theta, sigma, REMLcrit, VarCorr, isSingular,
# lmerTest's type-III anova (Satterthwaite and Kenward-Roger) and emmeans(m, pairwise ~ condition |
# iteration, adjust = "none") with lmer.df = "satterthwaite" and "kenward-roger" (the trend model
# at every observed iteration).
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, pbkrtest 0.5.2, emmeans 1.8.4-1, Matrix 1.5-3 (Debian 12).
# Optimiser: lme4's bobyqa (as lmer's default for the final fit) with rhoend 1e-12 and a large
# maxfun, so that R stops at the REML optimum to ~1e-10 rather than at its default rhoend 2e-7.
suppressPackageStartupMessages({ library(lme4); library(lmerTest); library(emmeans); library(pbkrtest) })
emm_options(lmerTest.limit = 1e6, pbkrtest.limit = 1e6)
ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e6),
                    calc.derivs = FALSE)
out <- list()
put <- function(ds, model, ddf, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(dataset = ds, model = model, ddf = ddf, quantity = quantity,
                                        name = name, value = sprintf("%.17g", value))

# n participants, every one sees every condition at every iteration (before `missing` drops
# trials); u0 the participant's intercept, u_c its deviation in each non-reference condition.
make_within <- function(ds, seed, n, conds, iters, cond_eff, trend, participant_sd = 0.15,
                        slope_sd = 0.12, missing = 0, only_one = character(0)) {
  set.seed(seed)
  ids <- sprintf("P%02d", seq_len(n))
  d <- expand.grid(iteration = iters, condition = conds, participant = ids, stringsAsFactors = FALSE)
  u0 <- setNames(rnorm(n, 0, participant_sd), ids)
  uc <- matrix(rnorm(n * length(conds), 0, slope_sd), n, length(conds), dimnames = list(ids, conds))
  uc[, 1] <- 0
  ci <- match(d$condition, conds)
  d$y <- round(0.5 + cond_eff[ci] + trend[ci] * (d$iteration - 1) + u0[d$participant] +
               uc[cbind(d$participant, d$condition)] + rnorm(nrow(d), 0, 0.1), 6)
  if (missing > 0) d <- d[-sample(nrow(d), round(missing * nrow(d))), ]
  for (p in only_one) d <- d[d$participant != p | d$condition == conds[1], ]
  d <- d[order(d$participant, d$condition, d$iteration), ]
  data.frame(dataset = ds, participant = d$participant, condition = d$condition,
             iteration = d$iteration, y = d$y)
}

anova_rows <- function(ds, model, m) {
  for (ddf in c("Satterthwaite", "Kenward-Roger")) {
    a <- anova(m, type = 3, ddf = ddf)
    for (t in rownames(a)) {
      put(ds, model, ddf, "NumDF", t, a[t, "NumDF"]); put(ds, model, ddf, "DenDF", t, a[t, "DenDF"])
      put(ds, model, ddf, "F", t, a[t, "F value"]); put(ds, model, ddf, "p", t, a[t, "Pr(>F)"])
      put(ds, model, ddf, "SumSq", t, a[t, "Sum Sq"])
    }
  }
}

emm_rows <- function(ds, model, m, d, trend) {
  for (ddf in c("satterthwaite", "kenward-roger")) {
    emm_options(lmer.df = ddf)
    e <- if (trend) emmeans(m, pairwise ~ condition | iteration, adjust = "none",
                            at = list(iteration = sort(unique(d$iteration))))
         else emmeans(m, pairwise ~ condition | iteration, adjust = "none")
    s <- as.data.frame(summary(e$contrasts, infer = c(TRUE, TRUE)))
    label <- if (ddf == "satterthwaite") "Satterthwaite" else "Kenward-Roger"
    for (i in seq_len(nrow(s))) {
      n <- paste0(as.character(s$contrast[i]), "|", as.character(s$iteration[i]))
      put(ds, model, label, "c.estimate", n, s$estimate[i]); put(ds, model, label, "c.SE", n, s$SE[i])
      put(ds, model, label, "c.df", n, s$df[i]); put(ds, model, label, "c.t", n, s$t.ratio[i])
      put(ds, model, label, "c.p", n, s$p.value[i])
    }
  }
}

fit_rows <- function(ds, model, m) {
  b <- fixef(m); for (nm in names(b)) put(ds, model, "", "beta", nm, b[nm])
  v <- diag(as.matrix(vcov(m))); for (nm in names(b)) put(ds, model, "", "vcov", nm, v[nm])
  va <- diag(as.matrix(vcovAdj(m))); for (i in seq_along(b)) put(ds, model, "", "vcov_adj", names(b)[i], va[i])
  th <- getME(m, "theta"); for (i in seq_along(th)) put(ds, model, "", "theta", i, th[i])
  put(ds, model, "", "sigma", "", sigma(m)); put(ds, model, "", "REMLcrit", "", REMLcrit(m))
  put(ds, model, "", "singular", "", as.numeric(isSingular(m)))
  vc <- as.data.frame(VarCorr(m))
  for (i in seq_len(nrow(vc))) {
    if (is.na(vc$var2[i])) put(ds, model, "", "variance", paste(vc$grp[i], vc$var1[i]), vc$vcov[i])
    else put(ds, model, "", "correlation", paste(vc$var1[i], vc$var2[i]), vc$sdcor[i])
  }
}

fit_all <- function(d) {
  ds <- d$dataset[1]
  d$condition <- factor(d$condition)
  df <- d; df$iteration <- factor(df$iteration)
  models <- list(
    f_int = lmer(y ~ condition * iteration + (1 | participant), df, REML = TRUE, control = ctrl),
    f_slope = lmer(y ~ condition * iteration + (1 + condition | participant), df, REML = TRUE,
                   control = ctrl),
    t_slope = lmer(y ~ condition * iteration + (1 + condition | participant), d, REML = TRUE,
                   control = ctrl))
  for (model in names(models)) {
    m <- models[[model]]
    fit_rows(ds, model, m)
    anova_rows(ds, model, m)
    emm_rows(ds, model, m, d, model == "t_slope")
  }
}

sets <- list(
  make_within("balanced2x5", 31, 16, c("adaptive", "random"), 1:5, c(0, 0.05), c(0, -0.01)),
  make_within("three3x4", 32, 15, c("adaptive", "random", "static"), 1:4, c(0, 0.06, -0.04),
              c(0, -0.01, 0.015)),
  make_within("unbalanced_missing", 33, 14, c("adaptive", "random", "static"), 1:4,
              c(0, 0.04, 0.02), c(0, 0.01, -0.02), missing = 0.12),
  make_within("one_condition_participant", 34, 14, c("adaptive", "random"), 1:5, c(0, 0.05),
              c(0, -0.01), missing = 0.05, only_one = c("P03", "P11")),
  # No participant x condition variance in the simulation: lme4 puts the slope's theta on the
  # boundary (theta 3 = 0, isSingular TRUE) in both slope models.
  make_within("singular", 36, 14, c("adaptive", "random"), 1:4, c(0, 0.03), c(0, 0.01),
              slope_sd = 0),
  make_within("strong_effect", 36, 12, c("adaptive", "random"), 1:5, c(0, 0.3), c(0, 0.08)))
for (d in sets) fit_all(d)
write.csv(do.call(rbind, sets), "lmm_within_data.csv", row.names = FALSE, quote = FALSE)
write.csv(do.call(rbind, out), "lmm_within_golden.csv", row.names = FALSE, quote = FALSE)
