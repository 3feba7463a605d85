#include "io/scene_overrides.hpp"

#include "model/input_error.hpp"

namespace lsi {

void apply_overrides(nlohmann::json& doc, const std::vector<std::string>& overrides) {
  using json = nlohmann::json;
  for (const std::string& o : overrides) {
    const std::string shown = "--set '" + o + "'";
    const auto eq = o.find('=');
    if (o.empty() || o[0] != '/' || eq == std::string::npos || eq == 1)
      throw InputError(shown + ": must be /json/pointer=value (e.g. /landslide/velocity_m_s=8)");
    const std::string path = o.substr(0, eq), text = o.substr(eq + 1);
    json::json_pointer pointer;
    try {
      pointer = json::json_pointer(path);
    } catch (const json::exception&) {
      throw InputError(shown + ": " + path + " is not a JSON pointer");
    }
    json value = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (value.is_discarded()) value = text;  // not JSON: a string
    const json::json_pointer parent = pointer.parent_pointer();
    if (!doc.contains(parent))
      throw InputError(shown + ": " + (parent.empty() ? "/" : parent.to_string()) +
                       " is not in the scene");
    json& container = doc[parent];
    if (container.is_array()) {
      const std::string& last = pointer.back();
      const bool append = last == "-";
      std::size_t index = 0;
      const bool number = !last.empty() && last.size() <= 18 &&
                          last.find_first_not_of("0123456789") == std::string::npos;
      if (number) index = std::stoull(last);
      if (!append && !(number && index < container.size()))
        throw InputError(shown + ": " + parent.to_string() + " has " +
                         std::to_string(container.size()) + " elements (index " + last +
                         " is not one of them; \"-\" appends)");
      if (append)
        container.push_back(value);
      else
        container[index] = value;
    } else if (container.is_object()) {
      container[pointer.back()] = value;
    } else {
      throw InputError(shown + ": " + parent.to_string() + " is a " + container.type_name() +
                       ", not an object or array");
    }
  }
}

}  // namespace lsi
