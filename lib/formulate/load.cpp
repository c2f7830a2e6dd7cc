#include "formulate/load.hpp"

#include "formulate/linkage.hpp"
#include "formulate/spherical.hpp"

namespace linkbox::formulate {

namespace {

struct Make {
  std::unique_ptr<Formulation> operator()(const model::System& s) const {
    return std::make_unique<PolynomialFormulation>(s);
  }
  std::unique_ptr<Formulation> operator()(const input::SphericalCase& c) const {
    return std::make_unique<SphericalFormulation>(c);
  }
  std::unique_ptr<Formulation> operator()(const input::LinkageCase& c) const {
    return std::make_unique<LinkageFormulation>(c);
  }
};

template <class Read>
LoadedCase load(const std::string& file, Read&& read) {
  try {
    const input::Case c = read();
    return {c.kind, c.name, c.file, formulate(c), c.solve};
  } catch (const input::InputError&) {
    throw;
  } catch (const std::exception& e) {  // a bug, not the user's fault, but still no crash
    throw input::InputError(file, 0, std::string("internal error while loading: ") + e.what());
  }
}

}  // namespace

std::unique_ptr<Formulation> formulate(const input::Case& c) { return std::visit(Make{}, c.description); }

LoadedCase load_case(const std::string& path) {
  return load(path, [&] { return input::read_case(path); });
}

LoadedCase load_case_text(std::string_view text, const std::string& file) {
  return load(file, [&] { return input::read_case_text(text, file); });
}

}  // namespace linkbox::formulate
