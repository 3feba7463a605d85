#include "model/study.hpp"

#include <algorithm>

namespace lsi {

bool Study::runs(const std::string& method) const {
  return std::find(methods.begin(), methods.end(), method) != methods.end();
}

std::vector<std::string> Study::output_columns() const {
  std::vector<std::string> c;
  for (const auto& m : methods)
    for (const auto& o : outputs) c.push_back(m + "/" + o);
  return c;
}

}  // namespace lsi
