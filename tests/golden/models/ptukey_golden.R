# Golden values of the studentized range distribution (R's ptukey / qtukey, Copenhaver & Holland
# 1988) for tests/models/test_studentized_range.cpp.   cd tests/golden/models && Rscript ptukey_golden.R
# R 4.2.2. Columns: q, nmeans, df, ptukey (lower tail), p (a probability), qtukey(p).
g <- expand.grid(q = c(0.5, 1.5, 2.8, 3.6, 5, 7.5), nmeans = c(2, 3, 5, 10, 20),
                 df = c(2, 5, 12.5, 22, 87.99, 300, Inf))
g$ptukey <- ptukey(g$q, g$nmeans, g$df)
g$p <- rep(c(0.5, 0.9, 0.95, 0.99, 0.999, 0.2), length.out = nrow(g))
g$qtukey <- qtukey(g$p, g$nmeans, g$df)
g[] <- lapply(g, function(x) sprintf("%.17g", x))
write.csv(g, "ptukey_golden.csv", row.names = FALSE, quote = FALSE)
