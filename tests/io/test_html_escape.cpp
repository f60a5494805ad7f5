// io::html_escape: the five characters that matter in HTML text and quoted attributes.
#include <gtest/gtest.h>

#include "feint/io/html_escape.hpp"

using feint::io::html_escape;

TEST(HtmlEscape, EscapesMarkupAndBothQuotes) {
  EXPECT_EQ(html_escape("<a href=\"x\">Tom & Jerry's</a>"),
            "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
}

TEST(HtmlEscape, LeavesOtherTextAndUtf8Alone) {
  EXPECT_EQ(html_escape(""), "");
  EXPECT_EQ(html_escape("condition \u00d7 iteration, \u03b7G\u00b2 = .031"),
            "condition \u00d7 iteration, \u03b7G\u00b2 = .031");
}

TEST(HtmlEscape, AnEscapedAmpersandIsEscapedAgain) { EXPECT_EQ(html_escape("&amp;"), "&amp;amp;"); }
