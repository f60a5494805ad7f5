# The exposure figure's fitted line and band (tests/plot/test_figure_rules.cpp, ExposureTrend):
# lm(y ~ exposure) with predict(interval = "confidence"). Run: Rscript exposure_ols.R
# Output (R 4.2.2):
#   (Intercept) 0.149999999999999911   x 0.050000000000000017
#   slope CI   -0.18293121861108708  0.28293121861108711
#   fit 0.2 / 0.25 / 0.3; lwr -0.055163365560919136 0.069572253901492076 -0.029414488459891752
#   upr 0.45516336556091896 0.43042774609850781 0.62941448845989156
x <- c(1, 2, 3, 1, 2); y <- c(0.1, 0.3, 0.2, 0.2, 0.4)
m <- lm(y ~ x); print(coef(m), digits = 17); print(confint(m)["x", ], digits = 17)
print(predict(m, data.frame(x = c(1, 2, 3)), interval = "confidence"), digits = 17)
