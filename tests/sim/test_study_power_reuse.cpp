// `feint power observer`'s reuse of work (include/feint/sim/study_power.hpp): the robot's paths
// computed once, and every size analysed on the same simulated people. Each study is rebuilt here
// from simulate_participant and the documented seeds, and must agree bit for bit.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "feint/rng.hpp"
#include "feint/sim/study.hpp"
#include "feint/sim/study_power.hpp"
#include "feint/stats/ttest.hpp"

using namespace feint::sim;

namespace {

/// A participant's mean trial error over iterations from..N, from simulate_participant.
double later_mean(const StudySettings& study, int index, int from) {
  const ParticipantRecord p = simulate_participant(study, index);
  double sum = 0;
  int n = 0;
  for (const auto& tr : p.trials) {
    if (tr.iteration < from) continue;
    sum += tr.error;
    ++n;
  }
  return sum / n;
}

double welch_p(const std::vector<double>& a, const std::vector<double>& r) {
  feint::stats::TestOptions o;
  o.alternative = feint::stats::Alternative::greater;
  return feint::stats::t_test_welch(a, r, o).p_value.value_or(1.0);
}

}  // namespace

// simulate_study_test computes each path once; its study is simulate_participant's.
TEST(StudyPowerReuse, PathsComputedOnceGiveSimulateParticipantsStudy) {
  StudySettings study;
  study.participants = 4;
  study.seed = 77;
  std::vector<double> a, r;
  for (int i = 0; i < 8; ++i) (i < 4 ? a : r).push_back(later_mean(study, i, 5));
  const StudyTest t = simulate_study_test(study, 5);
  EXPECT_EQ(t.p_value, welch_p(a, r));
  double ma = 0, mr = 0;
  for (int i = 0; i < 4; ++i) {
    ma += a[static_cast<std::size_t>(i)];
    mr += r[static_cast<std::size_t>(i)];
  }
  EXPECT_EQ(t.difference, ma / 4 - mr / 4);
}

// Study s has the seed SplitMix64(SplitMix64(seed) xor s); its participant k of condition c draws
// from stream 2k + c; the study of size n is the first n of each condition. simulate_participant
// draws participant `index` from stream `index`, in the condition index / participants: with
// participants = 2k + 1 index 2k is adaptive, with participants = k + 1 index 2k + 1 is random.
TEST(StudyPowerReuse, EverySizeIsAnalysedOnTheSamePeople) {
  StudyPowerSettings s;
  s.participants = {3, 5};
  s.studies = 12;
  s.seed = 4242;
  s.threads = 2;
  const StudyPowerResult res = study_power(s);
  std::uint64_t state = s.seed;
  const std::uint64_t key = feint::splitmix64(state);
  for (std::size_t i = 0; i < s.participants.size(); ++i) {
    const int n = s.participants[i];
    std::size_t rejected = 0;
    for (std::size_t k = 0; k < s.studies; ++k) {
      StudySettings study = s.study;
      std::uint64_t mix = key ^ k;
      study.seed = feint::splitmix64(mix);
      std::vector<double> a, r;
      for (int q = 0; q < n; ++q) {
        study.participants = 2 * q + 1;
        a.push_back(later_mean(study, 2 * q, s.from_iteration));
        study.participants = q + 1;
        r.push_back(later_mean(study, 2 * q + 1, s.from_iteration));
      }
      rejected += welch_p(a, r) < s.alpha;
    }
    EXPECT_EQ(res.points[i].power, static_cast<double>(rejected) / static_cast<double>(s.studies)) << "n = " << n;
  }
}

// The progress callback counts simulated participants up to the total (2 x the largest size x
// studies), never backwards.
TEST(StudyPowerReuse, ProgressCountsParticipantsUpToTheTotal) {
  StudyPowerSettings s;
  s.participants = {2, 3};
  s.studies = 10;
  s.threads = 2;
  std::vector<std::uint64_t> seen;
  std::uint64_t total = 0;
  s.on_progress = [&](std::uint64_t done, std::uint64_t all) {
    seen.push_back(done);
    total = all;
  };
  study_power(s);
  EXPECT_EQ(total, 2u * 3u * 10u);
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);
  EXPECT_LE(seen.back(), total);
}
