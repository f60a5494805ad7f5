# lmerTest's Satterthwaite df when the response is measured in small units.
#
#   cd tests/golden/models && Rscript scale_golden.R
#
# Fits error ~ condition * iteration + (1 | participant) (and the trend model with a random
# slope) to lmm_unbalanced4_missing.csv / lmm_trend_slope.csv with the response multiplied by
# 1e6 ... 1e-9, and writes lmerTest's type-III F, DenDF and p at each scale to scale_golden.csv.
# The exact answer does not depend on the scale; lmerTest's does below ~1e-5, because numDeriv
# (used by lmerTest to differentiate the REML deviance and vcov(beta) with respect to
# (theta, sigma)) takes an absolute step of 1e-4 when |sigma| < 1.8e-5, larger than sigma itself.
# tests/models/test_mixed_model_golden.cpp checks feint at every scale against R at scale 1 and
# that R's own values drift (docs/mixed-model.md shows the table).
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3.
suppressPackageStartupMessages({ library(lme4); library(lmerTest) })
ctrl <- lmerControl(optimizer = "nloptwrap",
                    optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14,
                                   ftol_rel = 1e-15, maxeval = 1e5),
                    calc.derivs = FALSE, check.conv.singular = "ignore")
out <- list()
for (case in c("unbalanced4_missing", "trend_slope")) {
  d <- read.csv(sprintf("lmm_%s.csv", case))
  d$condition <- factor(d$condition)
  if (case == "unbalanced4_missing") d$iteration <- factor(d$iteration)
  f <- if (case == "trend_slope") y ~ condition * iteration + (1 + iteration | participant)
       else y ~ condition * iteration + (1 | participant)
  for (scale in c(1e6, 1, 1e-3, 1e-5, 1e-6, 1e-7, 1e-9)) {
    d$y <- d$error * scale
    m <- lmer(f, d, REML = TRUE, control = ctrl)
    a <- tryCatch(anova(m, type = 3, ddf = "Satterthwaite"), error = function(e) NULL)
    for (t in c("condition", "iteration", "condition:iteration")) {
      v <- if (is.null(a)) c(NA, NA, NA) else c(a[t, "F value"], a[t, "DenDF"], a[t, "Pr(>F)"])
      out[[length(out) + 1]] <- data.frame(case = case, scale = sprintf("%g", scale), term = t,
                                           F = sprintf("%.17g", v[1]),
                                           DenDF = sprintf("%.17g", v[2]),
                                           p = sprintf("%.17g", v[3]))
    }
  }
}
write.csv(do.call(rbind, out), "scale_golden.csv", row.names = FALSE, quote = FALSE)
