// The one Term enum (core/render/term.h): storage order, names and parsing.
#include <gtest/gtest.h>

#include "core/render/term.h"

namespace test_term {

using namespace rrf;

TEST(Term, StorageOrderIsDirectIndirectGlobal) {
    // Images, reports, the GLSL predictor's colour attachments and the workbench all index with int(Term).
    EXPECT_EQ(int(Term::Direct), 0);
    EXPECT_EQ(int(Term::Indirect), 1);
    EXPECT_EQ(int(Term::Global), 2);
    for (int i = 0; i < kTermCount; ++i) EXPECT_EQ(int(kTerms[i]), i);
}

TEST(Term, NamesRoundTrip) {
    EXPECT_STREQ(termName(Term::Direct), "direct");
    EXPECT_STREQ(termName(Term::Indirect), "indirect");
    EXPECT_STREQ(termName(Term::Global), "global");
    for (Term t : kTerms) {
        ASSERT_TRUE(parseTerm(termName(t)).has_value()) << termName(t);
        EXPECT_EQ(*parseTerm(termName(t)), t);
    }
    EXPECT_FALSE(parseTerm("Global").has_value());
    EXPECT_FALSE(parseTerm("joint").has_value()) << "a network target, not a radiance term";
    EXPECT_FALSE(parseTerm("").has_value());
}

}  // namespace test_term
