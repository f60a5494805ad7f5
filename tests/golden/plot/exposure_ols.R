# The exposure figure's fitted line and its participant-clustered (CR1) band
# (tests/plot/test_figure_rules.cpp, ExposureTrend.MeansAndTheFittedLineAreRsLmWithClusteredErrors):
# lm(y ~ x) with the sandwich covariance computed by hand (the sandwich package's
# vcovCL(m, cluster = g, type = "HC1") gives the same). Run: Rscript exposure_ols.R
# Output (R 4.2.2):
#   (Intercept) 0.289999999999999980  x 0.010000000000000012
#   slope CI -0.15918373035071859 0.17918373035071861
#   fit  0.3 / 0.31 / 0.32 / 0.33
#   low  -0.1726977172233140068 -0.0036296768098073029 0.1452708218004628016 0.1887793694833634350
#   high  0.77269771722331404    0.62362967680980730    0.49472917819953721   0.47122063051663660
x <- c(1, 2, 3, 1, 2, 1, 2, 3, 4); y <- c(0.1, 0.3, 0.2, 0.2, 0.4, 0.5, 0.45, 0.3, 0.35)
g <- c("P1", "P1", "P1", "P2", "P2", "P3", "P3", "P3", "P3")
m <- lm(y ~ x); X <- model.matrix(m); e <- resid(m)
N <- nrow(X); K <- ncol(X); G <- length(unique(g))
bread <- solve(crossprod(X))
meat <- Reduce(`+`, lapply(split(seq_len(N), g), function(i) {
  s <- crossprod(X[i, , drop = FALSE], e[i]); s %*% t(s) }))
V <- G / (G - 1) * (N - 1) / (N - K) * bread %*% meat %*% bread
q <- qt(0.975, G - 1)
print(coef(m), digits = 17)
print(coef(m)[2] + c(-1, 1) * q * sqrt(V[2, 2]), digits = 17)
A <- cbind(1, 1:4); fit <- A %*% coef(m); se <- sqrt(rowSums((A %*% V) * A))
print(cbind(fit, fit - q * se, fit + q * se), digits = 17)
