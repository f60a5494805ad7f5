# Golden exposure slopes split by condition (tests/models/test_exposure_by_condition.cpp).
# Regenerate from tests/golden/models with R 4.2 (lme4, lmerTest):
#   cd tests/golden/models && Rscript exposure_by_condition_golden.R
# Data: lmm_exposure.csv (2 conditions x 3 strategies). In each condition separately:
#   lmer(error ~ strategy * exposure + (1 | participant), REML) and each strategy's exposure slope by
#   lmerTest::contest1D (Satterthwaite df). The difference of a strategy's slopes between the two
#   conditions (independent participants, so independent fits): estimate a - r, SE = sqrt(SEa^2 +
#   SEr^2), Welch-Satterthwaite df = (SEa^2 + SEr^2)^2 / (SEa^4/dfa + SEr^4/dfr), t, two-sided p, 95% CI.
suppressMessages({library(lme4); library(lmerTest)})
ctrl <- lmerControl(optimizer = "nloptwrap",
                    optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14,
                                   ftol_rel = 1e-15, maxeval = 1e5),
                    calc.derivs = FALSE)
g17 <- function(x) sprintf("%.17g", x)
d <- read.csv("lmm_exposure.csv")
d <- d[order(d$participant, d$iteration), ]
d$exposure <- ave(seq_len(nrow(d)), d$participant, d$strategy, FUN = seq_along) - 1
d$strategy <- factor(d$strategy)
slopes <- list()
for (cond in sort(unique(d$condition))) {
  dc <- d[d$condition == cond, ]
  m <- lmer(error ~ strategy * exposure + (1 | participant), dc, REML = TRUE, control = ctrl)
  for (s in levels(d$strategy)) {
    L <- setNames(rep(0, length(fixef(m))), names(fixef(m)))
    L["exposure"] <- 1
    if (s != levels(d$strategy)[1]) L[paste0("strategy", s, ":exposure")] <- 1
    ct <- contest1D(m, L, confint = TRUE)
    slopes[[length(slopes) + 1]] <- data.frame(kind = "slope", strategy = s, condition = cond,
      estimate = ct$Estimate, se = ct[["Std. Error"]], df = ct$df, t = ct[["t value"]],
      p = ct[["Pr(>|t|)"]], lower = ct$lower, upper = ct$upper)
  }
}
sl <- do.call(rbind, slopes)
diffs <- lapply(levels(d$strategy), function(s) {
  a <- sl[sl$strategy == s & sl$condition == "adaptive", ]; r <- sl[sl$strategy == s & sl$condition == "random", ]
  est <- a$estimate - r$estimate; se <- sqrt(a$se^2 + r$se^2)
  df <- (a$se^2 + r$se^2)^2 / (a$se^4 / a$df + r$se^4 / r$df); t <- est / se
  q <- qt(0.975, df)
  data.frame(kind = "difference", strategy = s, condition = "adaptive-random", estimate = est, se = se,
             df = df, t = t, p = 2 * pt(-abs(t), df), lower = est - q * se, upper = est + q * se)
})
out <- rbind(sl, do.call(rbind, diffs))
for (k in 4:10) out[[k]] <- g17(out[[k]])
write.csv(out, "exposure_by_condition_golden.csv", row.names = FALSE, quote = FALSE)
