#pragma once
/// JSON carried as text inside a typed struct: the keys of a newer file this build does not know,
/// kept so that a round trip through this build writes them back as they were. Typed headers hold
/// it without the JSON library; only the file codecs (files named *_json.* or *_file.*, and
/// core/util/json_reader.*) parse and write it, with jsonText() and parseJsonText() there.

#include <string>

namespace rrf {

struct JsonText {
    std::string text;  ///< compact JSON; empty when there is nothing (read as an empty object)
    bool empty() const { return text.empty() || text == "{}" || text == "null"; }
    bool operator==(const JsonText& o) const { return text == o.text; }
    bool operator!=(const JsonText& o) const { return !(*this == o); }
};

}  // namespace rrf
