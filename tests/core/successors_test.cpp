// The successor writer (core/successors.h) and what it hands the pool, a ModuleValue
// (core/module_value.h): a new cell goes out as its event's lineage key and its number
// in the rule, `me` and `=X` as the coordinates of the cell they come from; every id
// derived from those equals the one the engine has always given (successorId).

#include <gtest/gtest.h>

#include <vector>

#include "core/module_value.h"
#include "core/rule_evaluator.h"
#include "core/successors.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

TEST(ModuleValue, TheIdIsTheKeyMixedWithKOrTheKeyItself) {
  const ModuleValue made{2, 7, 1.5, 0x0123456789abcdefull};
  EXPECT_EQ(made.id(), mixKey(0x0123456789abcdefull, 7));
  const ModuleValue own{2, ModuleValue::kOwnId, 1.5, 0x0123456789abcdefull};
  EXPECT_EQ(own.id(), 0x0123456789abcdefull);
  const CellRecord record = recordOf(made);
  EXPECT_EQ(record.master, 2u);
  EXPECT_EQ(record.birth, 1.5);
  EXPECT_EQ(record.id, made.id());
  const ModuleValue back = moduleOf(record);
  EXPECT_EQ(back.k, ModuleValue::kOwnId);
  EXPECT_EQ(back.id(), made.id());
}

struct Emitted {
  ModuleValue module;
  std::vector<double> values;
};

class SuccessorWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    program_ = compileOrFail(
        "cell A(x = 1) { lifetime 2; rules { terminal: -> B(x) =C(x + 1) B(2) (B(0), 0.5); } }\n"
        "cell M(x = 1) { lifetime 2; rules { terminal: -> B(x) me; } }\n"
        "cell B(y = 0) { lifetime 1; }\n"
        "cell C(c = 0) { lifetime 1; }\n"
        "system s { pool linear; axiom A; }\n");
    ASSERT_NE(program_, nullptr);
    a_ = static_cast<uint32_t>(program_->findMaster("A"));
    b_ = static_cast<uint32_t>(program_->findMaster("B"));
    c_ = static_cast<uint32_t>(program_->findMaster("C"));
    m_ = static_cast<uint32_t>(program_->findMaster("M"));
  }

  // Fires the terminal rule of `parent`'s master for it at `when`, with x = 3.
  std::vector<Emitted> fire(const ModuleValue& parent, double when, BirthCause cause, uint64_t* born,
                            std::vector<LineageRecord>* log = nullptr) {
    const CompiledRule& rule = program_->masters[parent.master].terminalRules.at(0);
    std::vector<double> frame(ruleFrameSize(*program_), 0.0);
    frame[0] = 3;
    const FunctionTable functions = program_->functionTable();
    RandomStream random(1);
    const EvalContext context{frame.data(), EvalEnvironment{&random, 1}, &functions};
    SuccessorWriter writer(*program_);
    writer.recordLineage(log);
    std::vector<Emitted> out;
    *born = writer.write(rule, parent, frame.data(), when, cause, context,
                         [&](const ModuleValue& module, const double* values, uint32_t count) {
                           out.push_back({module, std::vector<double>(values, values + count)});
                         });
    return out;
  }

  std::shared_ptr<const Program> program_;
  uint32_t a_ = 0, b_ = 0, c_ = 0, m_ = 0;
};

TEST_F(SuccessorWriterTest, NewCellsShareTheirEventsKeyAndEqualsXKeepsTheParentsCoordinates) {
  const ModuleValue parent{a_, 4, 0.5, 0xfeedfacecafebeefull};
  uint64_t born = 0;
  std::vector<LineageRecord> log;
  const std::vector<Emitted> out = fire(parent, 2.5, BirthCause::Terminal, &born, &log);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(born, 4u);
  const uint64_t lineage = mixKey(parent.id(), keyOf(2.5));
  EXPECT_EQ(lineageKey(parent.id(), 2.5, BirthCause::Terminal), lineage);

  // B(x): the first successor.
  EXPECT_EQ(out[0].module.master, b_);
  EXPECT_EQ(out[0].module.key, lineage);
  EXPECT_EQ(out[0].module.k, 1u);
  EXPECT_EQ(out[0].module.birth, 2.5);
  EXPECT_EQ(out[0].module.id(), successorId(parent.id(), 2.5, BirthCause::Terminal, 1));
  EXPECT_EQ(out[0].values, std::vector<double>{3});
  // =C(x + 1): another master with the parent's coordinates, born now.
  EXPECT_EQ(out[1].module.master, c_);
  EXPECT_EQ(out[1].module.key, parent.key);
  EXPECT_EQ(out[1].module.k, parent.k);
  EXPECT_EQ(out[1].module.birth, 2.5);
  EXPECT_EQ(out[1].module.id(), parent.id());
  EXPECT_EQ(out[1].values, std::vector<double>{4});
  // B(2) and (B(0), 0.5): numbers 3 and 4 of the event, the last born half a second ago.
  EXPECT_EQ(out[2].module.k, 3u);
  EXPECT_EQ(out[2].module.key, lineage);
  EXPECT_EQ(out[2].module.id(), successorId(parent.id(), 2.5, BirthCause::Terminal, 3));
  EXPECT_EQ(out[3].module.k, 4u);
  EXPECT_EQ(out[3].module.birth, 2.0);
  EXPECT_EQ(out[3].module.id(), successorId(parent.id(), 2.5, BirthCause::Terminal, 4));

  // The lineage log has every birth, by id.
  ASSERT_EQ(log.size(), 4u);
  EXPECT_EQ(log[0], (LineageRecord{out[0].module.id(), parent.id(), 2.5}));
  EXPECT_EQ(log[1], (LineageRecord{parent.id(), parent.id(), 2.5}));
  EXPECT_EQ(log[3], (LineageRecord{out[3].module.id(), parent.id(), 2.5}));
}

TEST_F(SuccessorWriterTest, MeKeepsTheParentsCoordinatesAndIsNoBirth) {
  const ModuleValue parent{m_, 9, 0.5, 0xfeedfacecafebeefull};
  uint64_t born = 0;
  std::vector<LineageRecord> log;
  const std::vector<Emitted> out = fire(parent, 2.5, BirthCause::Terminal, &born, &log);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(born, 1u);
  EXPECT_EQ(log.size(), 1u);
  EXPECT_EQ(out[0].module.k, 1u);
  EXPECT_EQ(out[1].module.master, m_);
  EXPECT_EQ(out[1].module.key, parent.key);
  EXPECT_EQ(out[1].module.k, 9u);
  EXPECT_EQ(out[1].module.birth, 2.5) << "a terminal rule starts me's age again";
  EXPECT_EQ(out[1].values, std::vector<double>{3});
}

TEST_F(SuccessorWriterTest, APerStepRuleSaltsTheKeyAndMeKeepsItsBirth) {
  // A parent read back from a record: its id is its key.
  const ModuleValue parent = moduleOf(CellRecord{m_, 0, 0.25, 0x1234567887654321ull});
  uint64_t born = 0;
  const std::vector<Emitted> out = fire(parent, 1.0, BirthCause::StepRule, &born);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].module.key, mixKey(0x1234567887654321ull, keyOf(1.0)) ^ kStepRuleSalt);
  EXPECT_EQ(out[0].module.id(), successorId(0x1234567887654321ull, 1.0, BirthCause::StepRule, 1));
  EXPECT_EQ(out[1].module.birth, 0.25) << "me keeps its age in a per-step rule";
  EXPECT_EQ(out[1].module.id(), 0x1234567887654321ull);
}

// The table walk (pools/table_rewrite.h) hashes in parts: mixKey split into its first
// word's part, its second's and their join, and the terminal lineage from the first part
// of the cell's id with the death's part kept between calls, give the whole hashes.
TEST(TerminalLineage, EqualsTheLineageKeyOfATerminalEvent) {
  TerminalLineage lineage;
  const uint64_t ids[] = {0, 1, 0x1234567887654321ull, ~uint64_t{0}};
  const double deaths[] = {2.5, 2.5, -0.0, 0.0, 1e300, 3.0};
  for (const uint64_t id : ids)
    for (const double death : deaths) {
      EXPECT_EQ(mixKeyJoin(mixKeyFirst(id), mixKeySecond(keyOf(death))), mixKey(id, keyOf(death)));
      EXPECT_EQ(lineage(mixKeyFirst(id), death), lineageKey(id, death, BirthCause::Terminal)) << id << " " << death;
    }
}

}  // namespace
}  // namespace ontogen
