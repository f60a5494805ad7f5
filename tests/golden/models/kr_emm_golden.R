# Golden values for Kenward-Roger df and estimated marginal means / contrasts of feint's mixed
# model (tests/models/test_kr_emmeans_golden.cpp).
#
#   cd tests/golden/models && Rscript kr_emm_golden.R
#
# Writes lmm_single_trial.csv (unbalanced4_missing with participant P03 reduced to one trial),
# lmm_strong_effect.csv (balanced5 with a strong effect: p-values below 1e-6),
# lmm_missing_cell.csv (balanced5 without condition 'adaptive' at iteration 3, fitted with
# iteration as a trend) and kr_emm_golden.csv (case, ddf, quantity, name, value).
# Type-III ANOVA: lmerTest::anova(m, ddf = "Kenward-Roger") (pbkrtest::KRmodcomp) and
# "Satterthwaite"; contrasts and means: emmeans with lmer.df = "kenward-roger" / "satterthwaite".
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, pbkrtest 0.5.2, emmeans 1.8.4-1.
suppressPackageStartupMessages({ library(lme4); library(lmerTest); library(emmeans) })
emm_options(lmerTest.limit = 1e6, pbkrtest.limit = 1e6)
ctrl <- lmerControl(optimizer = "nloptwrap",
                    optCtrl = list(xtol_abs = 1e-14, ftol_abs = 1e-15, xtol_rel = 1e-14,
                                   ftol_rel = 1e-15, maxeval = 1e5),
                    calc.derivs = FALSE)
out <- list()
put <- function(case, ddf, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(case = case, ddf = ddf, quantity = quantity, name = name,
                                        value = sprintf("%.17g", value))

d <- read.csv("lmm_unbalanced4_missing.csv")
d <- d[d$participant != "P03" | d$iteration == 2, ]
write.csv(d, "lmm_single_trial.csv", row.names = FALSE, quote = FALSE)
d <- read.csv("lmm_balanced5.csv")
d <- d[!(d$condition == "adaptive" & d$iteration == 3), ]
write.csv(d, "lmm_missing_cell.csv", row.names = FALSE, quote = FALSE)
# A strong effect, for p-values far below 1e-6 (F p ~ 1e-8, contrasts' p to ~1e-12): balanced5
# with 0.1 * (iteration - 1) added to every 'adaptive' error.
d <- read.csv("lmm_balanced5.csv")
d$error <- sprintf("%.6f", d$error + ifelse(d$condition == "adaptive", 0.1 * (d$iteration - 1), 0))
write.csv(d, "lmm_strong_effect.csv", row.names = FALSE, quote = FALSE)

emm_rows <- function(case, ddf, label, e) {
  s <- as.data.frame(summary(e, infer = c(TRUE, TRUE)))
  lab <- apply(s[, intersect(c("condition", "iteration"), names(s)), drop = FALSE], 1,
               function(r) paste(trimws(r), collapse = "|"))
  for (i in seq_len(nrow(s))) {
    n <- lab[i]
    put(case, ddf, paste0(label, ".emmean"), n, s$emmean[i]); put(case, ddf, paste0(label, ".SE"), n, s$SE[i])
    put(case, ddf, paste0(label, ".df"), n, s$df[i])
    put(case, ddf, paste0(label, ".lower"), n, s$lower.CL[i]); put(case, ddf, paste0(label, ".upper"), n, s$upper.CL[i])
  }
}
con_rows <- function(case, ddf, label, ct) {
  s <- as.data.frame(summary(ct, infer = c(TRUE, TRUE)))
  by <- intersect(c("condition", "iteration"), names(s))
  for (i in seq_len(nrow(s))) {
    n <- paste(c(as.character(s$contrast[i]), vapply(by, function(b) as.character(s[[b]][i]), "")),
               collapse = "|")
    put(case, ddf, paste0(label, ".estimate"), n, s$estimate[i]); put(case, ddf, paste0(label, ".SE"), n, s$SE[i])
    put(case, ddf, paste0(label, ".df"), n, s$df[i]); put(case, ddf, paste0(label, ".t"), n, s$t.ratio[i])
    put(case, ddf, paste0(label, ".p"), n, s$p.value[i])
    put(case, ddf, paste0(label, ".lower"), n, s$lower.CL[i]); put(case, ddf, paste0(label, ".upper"), n, s$upper.CL[i])
  }
}

fit_case <- function(case, trend = FALSE, slope = FALSE) {
  d <- read.csv(sprintf("lmm_%s.csv", case))
  d$condition <- factor(d$condition)
  if (!trend) d$iteration <- factor(d$iteration)
  f <- if (slope) error ~ condition * iteration + (1 + iteration | participant)
       else error ~ condition * iteration + (1 | participant)
  m <- lmer(f, d, REML = TRUE, control = ctrl)
  for (ddf in c("Satterthwaite", "Kenward-Roger")) {
    a <- anova(m, type = 3, ddf = ddf)
    for (t in rownames(a)) {
      put(case, ddf, "SumSq", t, a[t, "Sum Sq"]); put(case, ddf, "MeanSq", t, a[t, "Mean Sq"])
      put(case, ddf, "NumDF", t, a[t, "NumDF"]); put(case, ddf, "DenDF", t, a[t, "DenDF"])
      put(case, ddf, "F", t, a[t, "F value"]); put(case, ddf, "p", t, a[t, "Pr(>F)"])
    }
    emm_options(lmer.df = tolower(ddf))
    if (trend) {
      at <- list(iteration = sort(unique(d$iteration)))
      con_rows(case, ddf, "cond_by_it",
               contrast(emmeans(m, ~ condition | iteration, at = at), "pairwise"))
      next
    }
    emm_rows(case, ddf, "cells", emmeans(m, ~ condition * iteration))
    emm_rows(case, ddf, "condition", emmeans(m, ~ condition))
    emm_rows(case, ddf, "iteration", emmeans(m, ~ iteration))
    e_ci <- emmeans(m, ~ condition | iteration)
    e_ic <- emmeans(m, ~ iteration | condition)
    con_rows(case, ddf, "cond_by_it", contrast(e_ci, "pairwise", adjust = "none"))
    for (adj in c("none", "holm", "tukey"))
      con_rows(case, ddf, paste0("it_by_cond.", adj), contrast(e_ic, "pairwise", adjust = adj))
    for (adj in c("none", "holm", "tukey"))
      con_rows(case, ddf, paste0("iteration.", adj), contrast(emmeans(m, ~ iteration), "pairwise", adjust = adj))
    con_rows(case, ddf, "poly_by_cond", contrast(e_ic, "poly"))
    con_rows(case, ddf, "poly", contrast(emmeans(m, ~ iteration), "poly"))
  }
}
fit_case("balanced5")
fit_case("unbalanced4_missing")
fit_case("single_trial")
fit_case("missing_cell", trend = TRUE)
fit_case("trend_slope", trend = TRUE, slope = TRUE)
fit_case("strong_effect")
write.csv(do.call(rbind, out), "kr_emm_golden.csv", row.names = FALSE, quote = FALSE)
