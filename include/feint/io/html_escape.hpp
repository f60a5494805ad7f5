// feint/io/html_escape.hpp - text made safe for an HTML page (report.html, feint collect's pages).
#pragma once

#include <string>
#include <string_view>

namespace feint::io {

/// Escapes & < > " ' (as &amp; &lt; &gt; &quot; &#39;) for HTML text and quoted attribute values.
std::string html_escape(std::string_view text);

}  // namespace feint::io
