# Golden values of the pairs of three or more conditions on the mixed model (models::emm_contrasts
# with EmmFamily::pairwise_condition: the findings' pairs of conditions, docs/findings.md "Three or
# more conditions"; tests/models/test_condition_pairs_golden.cpp): emmeans(m, pairwise ~ condition,
# adjust = "none" / "holm" / "tukey") on lmer, with lmer.df = "satterthwaite" and "kenward-roger".
#   cd tests/golden/models && Rscript condition_pairs_golden.R
# Writes condition_pairs_data.csv (dataset, participant, condition, iteration, y) and
# condition_pairs_golden.csv (dataset, model, ddf, quantity, name, value; %.17g). Data sets:
#   b3_balanced        between, 3 conditions x 6 participants, 4 iterations, complete
#   b4_unbalanced      between, 4 conditions of 4, 7, 5, 6 participants, 5 iterations, 8 % trials missing
#   w3_complete        within, 10 participants x 3 conditions x 4 iterations
#   w3_missing         within, 12 participants, 10 % trials missing, P05 in one condition only
#   w4_unbalanced      within, 4 conditions, 9 participants, 15 % trials missing
#   w3_strong          within, 10 participants, conditions far apart (p far below 1e-6)
# Models (REML, treatment coding, levels sorted): f_int y ~ condition * factor(iteration) +
# (1 | participant) on every set; f_slope with (1 + condition | participant) on the within sets.
# Tukey bounds: R's qtukey stops at |dq| < 1e-4, so the bounds from the root of R's own
# ptukey(q, k, df) = 0.95 (uniroot, tol 1e-14) are written too (tukey.lower_exact, upper_exact).
# Tukey p: R's is 1 - ptukey (off by up to 8e-9 absolute, 1.2 % of a p of 6.4e-7 here), so the
# upper tail integrated from its definition is written too (tukey.p_exact, ptukey_upper() below:
# P(Q > q) = int f_s(s) P(range > q s) ds, P(range > w) = k int phi(z) (Phi(z)^(k-1) -
# (Phi(z) - Phi(z - w))^(k-1)) dz with the difference of powers factored: no cancellation).
# R 4.2.2, lme4 1.1-31, lmerTest 3.1-3, pbkrtest 0.5.2, emmeans 1.8.4-1; bobyqa at rhoend 1e-12.
suppressPackageStartupMessages({ library(lme4); library(lmerTest); library(emmeans); library(pbkrtest) })
# P(Q > q) of the studentized range of k means with df, from its definition: no 1 - P
up_range <- function(w, k) sapply(w, function(ww) {
  f <- function(z) { a <- pnorm(z); b <- pnorm(z - ww); s <- 0
    for (j in 0:(k - 2)) s <- s + a^j * (a - b)^(k - 2 - j)
    k * dnorm(z) * b * s }
  # the integrand peaks near z = 0 and z = w / 2 (phi(z) Phi(z - w) for a large w)
  br <- sort(unique(c(-Inf, -12, seq(-6, 6, by = 2), ww / 2 + seq(-12, 12, by = 2), Inf)))
  tot <- 0
  for (i in seq_len(length(br) - 1)) {
    r <- integrate(f, br[i], br[i + 1], rel.tol = 1e-13, abs.tol = 0, subdivisions = 2000L, stop.on.error = FALSE)
    if (r$message != "OK" && r$value > 1e-300) stop(r$message)
    tot <- tot + r$value
  }
  tot })
ptukey_upper <- function(q, k, df) {
  ds <- function(s) 2 * df * s * dchisq(df * s^2, df)
  g <- function(s) ds(s) * up_range(q * s, k)
  br <- c(0, qchisq(c(1e-12, 1e-6, 0.01, 0.5, 0.99, 1 - 1e-9), df) |> (\(x) sqrt(x / df))(), Inf); tot <- 0
  for (i in seq_len(length(br) - 1)) tot <- tot + integrate(g, br[i], br[i + 1], rel.tol = 1e-12, abs.tol = 0,
                                                           subdivisions = 2000L)$value
  tot }

emm_options(lmerTest.limit = 1e6, pbkrtest.limit = 1e6)
ctrl <- lmerControl(optimizer = "bobyqa", optCtrl = list(rhoend = 1e-12, maxfun = 1e6), calc.derivs = FALSE)
out <- list()
put <- function(ds, model, ddf, quantity, name, value)
  out[[length(out) + 1]] <<- data.frame(dataset = ds, model = model, ddf = ddf, quantity = quantity,
                                        name = name, value = sprintf("%.17g", value))

conds4 <- c("adaptive", "fixed", "honest", "random")
make_set <- function(ds, seed, within, sizes, k, iters, eff, missing = 0, only_one = character(0), sd_p = 0.12,
                     sd_c = 0.08) {
  set.seed(seed)
  conds <- conds4[seq_len(k)]
  rows <- list()
  n <- if (within) sizes else sum(sizes)
  for (i in seq_len(n)) {
    u0 <- rnorm(1, 0, sd_p); uc <- rnorm(k, 0, sd_c)
    mine <- if (within) seq_len(k) else rep(seq_len(k), sizes)[i]
    for (c in mine) {
      y <- 0.5 + eff[c] + u0 + (if (within) uc[c] else 0) - 0.01 * seq_len(iters) + rnorm(iters, 0, 0.1)
      rows[[length(rows) + 1]] <- data.frame(dataset = ds, participant = sprintf("P%02d", i),
                                             condition = conds[c], iteration = seq_len(iters), y = round(y, 6))
    }
  }
  d <- do.call(rbind, rows)
  if (missing > 0) d <- d[-sample(nrow(d), round(missing * nrow(d))), ]
  for (p in only_one) d <- d[d$participant != p | d$condition == conds[1], ]
  d
}
sets <- list(
  list(make_set("b3_balanced", 11, FALSE, c(6, 6, 6), 3, 4, c(0, 0.08, -0.05)), FALSE),
  list(make_set("b4_unbalanced", 12, FALSE, c(4, 7, 5, 6), 4, 5, c(0, 0.05, 0.1, -0.03), missing = 0.08), FALSE),
  list(make_set("w3_complete", 13, TRUE, 10, 3, 4, c(0, 0.04, -0.03)), TRUE),
  list(make_set("w3_missing", 14, TRUE, 12, 3, 4, c(0, 0.05, 0.02), missing = 0.10, only_one = "P05"), TRUE),
  list(make_set("w4_unbalanced", 15, TRUE, 9, 4, 3, c(0, 0.03, 0.06, -0.02), missing = 0.15), TRUE),
  list(make_set("w3_strong", 16, TRUE, 10, 3, 3, c(0, 0.25, -0.2), sd_c = 0.03), TRUE))
write.csv(do.call(rbind, lapply(sets, `[[`, 1)), "condition_pairs_data.csv", row.names = FALSE, quote = FALSE)

for (s in sets) {
  d <- s[[1]]; ds <- d$dataset[1]; k <- length(unique(d$condition))
  d$condition <- factor(d$condition); d$fi <- factor(d$iteration)
  models <- list(f_int = y ~ condition * fi + (1 | participant))
  if (s[[2]]) models$f_slope <- y ~ condition * fi + (1 + condition | participant)
  for (mn in names(models)) {
    m <- suppressMessages(lmer(models[[mn]], data = d, REML = TRUE, control = ctrl))
    for (ddf in c("satterthwaite", "kenward-roger")) {
      emm_options(lmer.df = ddf)
      label <- if (ddf == "satterthwaite") "Satterthwaite" else "Kenward-Roger"
      for (adj in c("none", "holm", "tukey")) {
        e <- suppressMessages(emmeans(m, pairwise ~ condition, adjust = adj))
        r <- as.data.frame(summary(e$contrasts, infer = c(TRUE, TRUE)))
        for (i in seq_len(nrow(r))) {
          n <- as.character(r$contrast[i])
          for (q in c("estimate", "SE", "df", "t.ratio", "p.value", "lower.CL", "upper.CL"))
            put(ds, mn, label, paste0(adj, ".", q), n, r[[q]][i])
          if (adj == "tukey") {
            qq <- uniroot(function(q) ptukey(q, k, r$df[i]) - 0.95, c(1, 20), tol = 1e-14)$root
            put(ds, mn, label, "tukey.lower_exact", n, r$estimate[i] - qq / sqrt(2) * r$SE[i])
            put(ds, mn, label, "tukey.upper_exact", n, r$estimate[i] + qq / sqrt(2) * r$SE[i])
            put(ds, mn, label, "tukey.p_exact", n, ptukey_upper(abs(r$t.ratio[i]) * sqrt(2), k, r$df[i]))
          }
        }
      }
    }
    put(ds, mn, "", "REMLcrit", "", REMLcrit(m)); put(ds, mn, "", "singular", "", as.numeric(isSingular(m)))
  }
}
write.csv(do.call(rbind, out), "condition_pairs_golden.csv", row.names = FALSE, quote = FALSE)
