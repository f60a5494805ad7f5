# Golden values of the pointer-trace measures (docs/pointer-measures.md) from the R package
# mousetrap's own code, on an extract of its data set KH2017 (Kieslich & Henninger, 2017) and on a
# few synthetic traces that reach the branches KH2017 does not (no movement, continuous movement,
# a start equal to the end, a path ending to the right of or below its start, ties).
#
# mousetrap: DESCRIPTION Version 3.2.3.9000, github.com/PascalKieslich/mousetrap commit
# 8dbae23ed78fca6150f8cc5a3dedcf1e7f8f0734 (2026-01-09). mousetrap is not installed: this script
# source()s its R files (R/utils.R, add.R, preprocess.R, import.R, deviations.R, derivatives.R,
# measures.R) from an unpacked copy of that commit, and reads data/KH2017_raw.rda and
# data/KH2017.rda from it. Its only other need is pracma (pracma::polyarea, for AUC; 2.4.2 here,
# R 4.2.2, Debian 12). Run from this folder:
#   git clone https://github.com/PascalKieslich/mousetrap /tmp/mousetrap
#   git -C /tmp/mousetrap checkout 8dbae23ed78fca6150f8cc5a3dedcf1e7f8f0734
#   Rscript mousetrap_golden.R /tmp/mousetrap
# Writes
#   kh2017_extract.csv        the extract: every correct trial of subjects 1-3 as mt_import_mousetrap
#                             imports it (timestamps reset to 0, duplicate timestamps removed,
#                             pixels, y downwards); mt_id, subject, trial, t, x, y
#   synthetic_traces.csv      the synthetic traces (same columns, subject "synthetic")
#   kh2017_measures.csv       one row per trial of both: mt_measures after the pipeline below
#   kh2017_time_normalized.csv mt_time_normalize (101 steps) of 10 KH2017 trials and every synthetic one
# Pipeline (KH2017's own, see ?KH2017): mt_remap_symmetric (defaults), mt_align_start(start = c(0,
# 0)), mt_derivatives (defaults), mt_measures (defaults; then again with flip_threshold = 20,
# initiation_threshold = 10, hover_threshold = 100 with and without the initial phase), and
# mt_time_normalize (defaults) followed by mt_measures on the normalised traces (columns tn_*).
args <- commandArgs(trailingOnly = TRUE)
if (length(args) < 1) stop("usage: Rscript mousetrap_golden.R MOUSETRAP_SOURCE_DIR")
src <- args[1]
commit <- "8dbae23ed78fca6150f8cc5a3dedcf1e7f8f0734"
version <- read.dcf(file.path(src, "DESCRIPTION"), fields = "Version")[1, 1]
stopifnot(version == "3.2.3.9000")
for (f in c("utils", "add", "preprocess", "import", "deviations", "derivatives", "measures"))
  source(file.path(src, "R", paste0(f, ".R")))
load(file.path(src, "data", "KH2017_raw.rda"))
load(file.path(src, "data", "KH2017.rda"))
stamp <- sprintf("# mousetrap %s (commit %s), R %s, pracma %s", version, commit,
                 paste(R.version$major, R.version$minor, sep = "."), packageVersion("pracma"))
num <- function(v) ifelse(is.na(v), "NA", sprintf("%.17g", v))
write_with_stamp <- function(df, file, what) {
  con <- file(file, "w")
  writeLines(c(stamp, paste("#", what)), con)
  write.csv(df, con, row.names = FALSE, quote = FALSE)
  close(con)
}

# KH2017 as documented: correct trials, imported, remapped, start aligned to (0, 0). Check that
# this reproduces the shipped KH2017 exactly before taking the extract from it.
raw <- KH2017_raw[KH2017_raw$correct == 1, ]
kh <- mt_import_mousetrap(raw)
pre <- mt_align_start(mt_remap_symmetric(kh), start = c(0, 0))
stopifnot(identical(pre$trajectories, KH2017$trajectories))
keep <- kh$data$subject_nr %in% 1:3
imported <- kh$trajectories[keep, , , drop = FALSE]
info <- data.frame(mt_id = rownames(imported), subject = kh$data$subject_nr[keep],
                   trial = kh$data$count_trial[keep])

# Synthetic traces in the imported coordinates (before remapping); t in ms, x and y in pixels.
tr <- function(id, t, x, y) list(id = id, t = t, x = x, y = y)
synthetic <- list(
  # moves at every sample, first timestamp 150: idle_time = hover_time = 150, hovers 0 (and -1
  # without the initial phase: mousetrap subtracts one hover that it never counted)
  tr("continuous", c(150, 160, 170, 185, 195), c(0, 10, -20, -40, -60), c(0, -30, -70, -90, -120)),
  # never moves: idle_time = RT, one hover; start = end (deviations are distances from the start)
  tr("still", c(0, 20, 40, 130), c(5, 5, 5, 5), c(-7, -7, -7, -7)),
  # two samples only
  tr("two_samples", c(0, 16), c(0, -300), c(0, -400)),
  # ends to the right of and above its start after remapping: AUC's sign is flipped
  tr("ends_right", c(0, 10, 20, 30, 40), c(-100, -120, -60, -90, -50), c(0, -40, -60, -150, -200)),
  # ends below its start after remapping: every deviation's sign is flipped, and AUC's
  tr("ends_below", c(0, 10, 20, 30), c(0, 40, -60, -100), c(-50, -20, -30, -10)),
  # ends where it started
  tr("round_trip", c(0, 10, 25, 45, 50), c(0, -50, -80, -20, 0), c(0, -60, -20, -10, 0)),
  # vertical direct path: deviations +/-30 tie (a vertical path has no point below it: both +30)
  tr("vertical_tie", c(0, 10, 20, 30, 40), c(0, 30, -30, 0, 0), c(0, -40, -80, -120, -160)),
  # x wiggles of 15 and 25 px (flip_threshold 20) and samples exactly on x = 0 (reversals)
  tr("wiggles", 10 * (0:9), c(0, 25, 10, 0, -15, 0, -25, -10, -35, -60),
     c(0, -10, -20, -30, -40, -50, -60, -70, -80, -90)),
  # pauses of exactly 100 ms and of 110 ms (hover_threshold 100: only the second counts), an
  # initial pause of 120 ms, and a last sample that does not move
  tr("hovers", c(0, 60, 120, 130, 180, 230, 240, 300, 350, 360, 380),
     c(0, 0, 0, -10, -10, -10, -40, -40, -40, -50, -50),
     c(0, 0, 0, -30, -30, -30, -60, -60, -60, -100, -100))
)
max_n <- max(dim(imported)[2], vapply(synthetic, function(s) length(s$t), 0L))
syn <- array(NA_real_, dim = c(length(synthetic), max_n, 3),
             dimnames = list(vapply(synthetic, `[[`, "", "id"), NULL, c("timestamps", "xpos", "ypos")))
for (i in seq_along(synthetic)) {
  n <- length(synthetic[[i]]$t)
  syn[i, 1:n, ] <- cbind(synthetic[[i]]$t, synthetic[[i]]$x, synthetic[[i]]$y)
}
imp <- array(NA_real_, dim = c(dim(imported)[1], max_n, 3), dimnames = list(rownames(imported), NULL,
             dimnames(imported)[[3]]))
imp[, seq_len(dim(imported)[2]), ] <- imported
traces <- array(NA_real_, dim = c(dim(imp)[1] + dim(syn)[1], max_n, 3),
                              dimnames = list(c(rownames(imp), rownames(syn)), NULL, dimnames(imp)[[3]]))
traces[seq_len(dim(imp)[1]), , ] <- imp
traces[dim(imp)[1] + seq_len(dim(syn)[1]), , ] <- syn
info <- rbind(info, data.frame(mt_id = rownames(syn), subject = "synthetic", trial = seq_len(dim(syn)[1])))

long <- function(a, rows) {
  do.call(rbind, lapply(seq_len(nrow(rows)), function(r) {
    id <- rows$mt_id[r]
    n <- sum(!is.na(a[id, , "timestamps"]))
    data.frame(rows[r, ], t = num(a[id, 1:n, "timestamps"]), x = num(a[id, 1:n, "xpos"]),
               y = num(a[id, 1:n, "ypos"]), row.names = NULL)
  }))
}
is_kh <- info$subject != "synthetic"
write_with_stamp(long(traces, info[is_kh, ]),
                 "kh2017_extract.csv", paste("KH2017 (Kieslich & Henninger, 2017), correct trials of",
                 "subjects 1-3 as mt_import_mousetrap imports them: t ms from the first sample, x/y px"))
write_with_stamp(long(traces, info[!is_kh, ]),
                 "synthetic_traces.csv", "synthetic traces (mousetrap_golden.R), imported coordinates")

# The pipeline and the measures.
p <- mt_align_start(mt_remap_symmetric(traces), start = c(0, 0))
p <- mt_derivatives(p)
base <- suppressMessages(suppressWarnings(mt_measures(p)))
pick <- function(m, cols, suffix) setNames(m[, cols, drop = FALSE], paste0(cols, suffix))
m_flip <- suppressMessages(suppressWarnings(mt_measures(p, flip_threshold = 20)))
m_init <- suppressMessages(suppressWarnings(mt_measures(p, initiation_threshold = 10)))
m_hov <- suppressMessages(suppressWarnings(mt_measures(p, hover_threshold = 100)))
m_hov0 <- suppressMessages(suppressWarnings(mt_measures(p, hover_threshold = 100,
                                                        hover_incl_initial = FALSE)))
tn <- mt_time_normalize(p)
m_tn <- suppressMessages(suppressWarnings(mt_measures(tn)))
# Left out (NA): the deviation measures of the normalised two_samples and vertical_tie traces.
# Their interpolated points lie on the direct path or a vertical one, where each deviation's sign
# and the place of the maximum are decided by the last bit of the projection: golden values for
# them would test rounding, not definitions.
degenerate <- c("two_samples", "vertical_tie")
m_tn[degenerate, c("MAD", "MAD_time", "MD_above", "MD_above_time", "MD_below", "MD_below_time",
                   "AD")] <- NA
out <- cbind(info, base[info$mt_id, -1],
             pick(m_flip[info$mt_id, ], c("xpos_flips", "ypos_flips"), "_flip20"),
             pick(m_init[info$mt_id, ], "initiation_time", "_init10"),
             pick(m_hov[info$mt_id, ], c("hover_time", "hovers"), "_hover100"),
             pick(m_hov0[info$mt_id, ], c("hover_time", "hovers"), "_hover100_noinitial"),
             setNames(m_tn[info$mt_id, -1], paste0("tn_", colnames(m_tn)[-1])))
for (j in 4:ncol(out)) out[[j]] <- num(out[[j]])
write_with_stamp(out, "kh2017_measures.csv", paste(
  "mt_measures after mt_remap_symmetric, mt_align_start(c(0,0)), mt_derivatives; *_flip20:",
  "flip_threshold = 20; *_init10: initiation_threshold = 10; *_hover100: hover_threshold = 100",
  "(*_noinitial: hover_incl_initial = FALSE); tn_*: mt_measures after mt_time_normalize(nsteps = 101)"))

tn_ids <- c(info$mt_id[is_kh][1:10], info$mt_id[!is_kh])
tn_long <- do.call(rbind, lapply(tn_ids, function(id)
  data.frame(mt_id = id, step = tn[id, , "steps"], t = num(tn[id, , "timestamps"]),
             x = num(tn[id, , "xpos"]), y = num(tn[id, , "ypos"]))))
write_with_stamp(tn_long, "kh2017_time_normalized.csv",
                 "mt_time_normalize(nsteps = 101) after mt_remap_symmetric and mt_align_start(c(0,0))")
