# Golden values for feint's linear mixed model (tests/models/test_mixed_model_golden.cpp).
#
#   cd tests/golden/models && Rscript lmm_golden.R
#
# Writes the data sets lmm_<case>.csv (scores format) and lmm_golden.csv (case, quantity, name,
# value). R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, emmeans 1.8.4-1 (Debian 12 packages).
# The fits use tight optimiser tolerances so that the values are the REML optimum to ~1e-10, not
# lme4's default stopping point; emmeans' df are pinned to Satterthwaite (lmer.df =
# "satterthwaite"; emmeans' default is Kenward-Roger when pbkrtest is installed, as on Debian).
suppressPackageStartupMessages({ library(lme4); library(lmerTest); library(emmeans) })
emm_options(lmer.df = "satterthwaite", lmerTest.limit = 1e6, pbkrtest.limit = 0)
ctrl <- lmerControl(optimizer = "nloptwrap",
                    optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14,
                                   ftol_rel = 1e-15, maxeval = 1e5),
                    calc.derivs = FALSE)
out <- list()
put <- function(case, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(case = case, quantity = quantity, name = name,
                                        value = sprintf("%.17g", value))

make_data <- function(n_a, n_b, iters, missing = 0, slope_sd = 0, strategies = NULL, seed = 1,
                      participant_sd = 0.08) {
  set.seed(seed)
  ids <- sprintf("P%02d", seq_len(n_a + n_b))
  cond <- rep(c("adaptive", "random"), c(n_a, n_b))
  d <- expand.grid(iteration = iters, k = seq_along(ids))
  d$participant <- ids[d$k]
  d$condition <- cond[d$k]
  u <- rnorm(length(ids), 0, participant_sd)[d$k]
  s <- rnorm(length(ids), 0, slope_sd)[d$k]
  eff <- ifelse(d$condition == "adaptive", 0.02, -0.01 * (d$iteration - 1) / max(1, length(iters)))
  d$error <- round(0.5 + eff + u + s * d$iteration + rnorm(nrow(d), 0, 0.1), 6)
  if (!is.null(strategies)) d$strategy <- sample(strategies, nrow(d), replace = TRUE)
  if (missing > 0) d <- d[-sample(nrow(d), round(missing * nrow(d))), ]
  d$k <- NULL
  d <- d[order(d$participant, d$iteration), ]
  d
}

anova_golden <- function(case, m) {
  a <- anova(m, type = 3, ddf = "Satterthwaite")
  for (t in rownames(a)) {
    put(case, "SumSq", t, a[t, "Sum Sq"]); put(case, "MeanSq", t, a[t, "Mean Sq"])
    put(case, "NumDF", t, a[t, "NumDF"]); put(case, "DenDF", t, a[t, "DenDF"])
    put(case, "F", t, a[t, "F value"]); put(case, "p", t, a[t, "Pr(>F)"])
  }
  put(case, "REMLcrit", "", REMLcrit(m)); put(case, "sigma", "", sigma(m))
  th <- getME(m, "theta"); for (i in seq_along(th)) put(case, "theta", i, th[i])
  b <- fixef(m); for (nm in names(b)) put(case, "beta", nm, b[nm])
  vc <- as.data.frame(VarCorr(m))
  for (i in seq_len(nrow(vc))) put(case, "vcov", paste(vc$grp[i], vc$var1[i], vc$var2[i]), vc$vcov[i])
}

contrast_golden <- function(case, m, at = NULL) {
  e <- if (is.null(at)) emmeans(m, pairwise ~ condition | iteration, adjust = "none")
       else emmeans(m, pairwise ~ condition | iteration, adjust = "none", at = at)
  ct <- as.data.frame(summary(e$contrasts, infer = c(TRUE, TRUE)))
  holm <- p.adjust(ct$p.value, "holm")
  for (i in seq_len(nrow(ct))) {
    it <- as.character(ct$iteration[i])
    put(case, "c.estimate", it, ct$estimate[i]); put(case, "c.SE", it, ct$SE[i])
    put(case, "c.df", it, ct$df[i]); put(case, "c.t", it, ct$t.ratio[i])
    put(case, "c.p", it, ct$p.value[i]); put(case, "c.p_holm", it, holm[i])
    put(case, "c.lower", it, ct$lower.CL[i]); put(case, "c.upper", it, ct$upper.CL[i])
  }
}

fit_factor <- function(case, d) {
  write.csv(d, sprintf("lmm_%s.csv", case), row.names = FALSE, quote = FALSE)
  d$iteration <- factor(d$iteration); d$condition <- factor(d$condition)
  m <- lmer(error ~ condition * iteration + (1 | participant), d, REML = TRUE, control = ctrl)
  anova_golden(case, m)
  contrast_golden(case, m)
}

fit_trend <- function(case, d, slope) {
  write.csv(d, sprintf("lmm_%s.csv", case), row.names = FALSE, quote = FALSE)
  d$condition <- factor(d$condition)
  f <- if (slope) error ~ condition * iteration + (1 + iteration | participant)
       else error ~ condition * iteration + (1 | participant)
  m <- lmer(f, d, REML = TRUE, control = ctrl)
  anova_golden(case, m)
  contrast_golden(case, m, at = list(iteration = sort(unique(d$iteration))))
}

# Iteration as a factor.
fit_factor("balanced5", make_data(12, 12, 1:5, seed = 11))
fit_factor("unbalanced4_missing", make_data(10, 14, 1:4, missing = 0.1, seed = 12))
fit_factor("two_iterations", make_data(9, 7, 1:2, missing = 0.05, seed = 13))
fit_factor("paper20_missing", make_data(30, 30, 1:20, missing = 0.03, seed = 14))
# No participant variance: a singular fit (theta = 0), Satterthwaite at the boundary.
fit_factor("singular", make_data(10, 10, 1:3, seed = 22, participant_sd = 0))
# One condition: the one-way repeated-measures model (lmerTest's type-I hypotheses for one term).
d1 <- make_data(14, 0, 1:4, missing = 0.05, seed = 22)
write.csv(d1, "lmm_one_condition.csv", row.names = FALSE, quote = FALSE)
d1$iteration <- factor(d1$iteration)
anova_golden("one_condition", lmer(error ~ iteration + (1 | participant), d1, control = ctrl))
# Linear trend, random intercept and random slope.
fit_trend("trend_intercept", make_data(15, 11, 1:8, missing = 0.05, seed = 15), slope = FALSE)
fit_trend("trend_slope", make_data(15, 13, 1:10, missing = 0.05, slope_sd = 0.02, seed = 16),
          slope = TRUE)

# Exposure: how often the participant had seen the trial's strategy before (0 = first time).
d <- make_data(10, 10, 1:12, missing = 0.05, strategies = c("ambiguous", "exaggerating", "switching"),
               seed = 17)
write.csv(d, "lmm_exposure.csv", row.names = FALSE, quote = FALSE)
d <- d[order(d$participant, d$iteration), ]
d$exposure <- ave(seq_len(nrow(d)), d$participant, d$strategy, FUN = seq_along) - 1
d$strategy <- factor(d$strategy)
m <- lmer(error ~ strategy * exposure + (1 | participant), d, REML = TRUE, control = ctrl)
anova_golden("exposure", m)
L <- matrix(0, 3, length(fixef(m)), dimnames = list(levels(d$strategy), names(fixef(m))))
L[, "exposure"] <- 1
L["exaggerating", "strategyexaggerating:exposure"] <- 1
L["switching", "strategyswitching:exposure"] <- 1
s <- contest(m, L, joint = FALSE, confint = TRUE)
for (i in seq_len(nrow(L))) {
  lv <- rownames(L)[i]
  put("exposure", "s.estimate", lv, s$Estimate[i]); put("exposure", "s.SE", lv, s[["Std. Error"]][i])
  put("exposure", "s.df", lv, s$df[i]); put("exposure", "s.t", lv, s[["t value"]][i])
  put("exposure", "s.p", lv, s[["Pr(>|t|)"]][i])
  put("exposure", "s.lower", lv, s$lower[i]); put("exposure", "s.upper", lv, s$upper[i])
}

write.csv(do.call(rbind, out), "lmm_golden.csv", row.names = FALSE, quote = FALSE)
