# Golden type-III ANOVA tables (lmerTest's anova(m), Satterthwaite) of the models with the
# strategy as a random effect, on the data sets of crossed_golden.R (crossed_data.csv):
#
#   cd tests/golden/models && Rscript crossed_anova_golden.R
#
# Writes crossed_anova_golden.csv (dataset, model, term, quantity, value): NumDF, DenDF, F value,
# Pr(>F) of every term. Models and optimiser settings as crossed_golden.R (R 4.2.2, lme4 1.1-31,
# lmerTest 3.1-3).
suppressPackageStartupMessages({ library(lme4); library(lmerTest) })
ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e6),
                    calc.derivs = FALSE)
all <- read.csv("crossed_data.csv", stringsAsFactors = FALSE)
out <- list()
for (ds in unique(all$dataset)) {
  d <- all[all$dataset == ds, ]
  d$condition <- factor(d$condition); d$strategy <- factor(d$strategy)
  if (ds != "trend") d$iteration <- factor(d$iteration)
  models <- list(
    crossed = lmer(y ~ condition * iteration + (1 | participant) + (1 | strategy), d,
                   REML = TRUE, control = ctrl),
    nested = lmer(y ~ condition * iteration + (1 | participant) + (1 | participant:strategy), d,
                  REML = TRUE, control = ctrl))
  for (model in names(models)) {
    a <- anova(models[[model]])
    for (term in rownames(a))
      for (q in c("NumDF", "DenDF", "F value", "Pr(>F)"))
        out[[length(out) + 1]] <- data.frame(dataset = ds, model = model, term = term,
                                             quantity = q, value = sprintf("%.17g", a[term, q]))
  }
}
write.csv(do.call(rbind, out), "crossed_anova_golden.csv", row.names = FALSE, quote = FALSE)
