#include "solve/certifier.hpp"

namespace linkbox::solve {

NaturalCertifier::NaturalCertifier(const formulate::Formulation& f, size_t sub, newton::NewtonOptions options)
    : f_(f), sub_(sub), options_(options) {}

const NaturalCertifier::Chart& NaturalCertifier::chart(std::uint64_t c) {
  auto it = charts_.find(c);
  if (it != charts_.end()) return it->second;
  Chart built;
  const formulate::NaturalSystem& sys = f_.natural(c);
  if (sys.compiled) built.system = newton::SquareSystem::all_unknown(sys.compiled);
  built.domain = sys.domain;
  return charts_.emplace(c, std::move(built)).first->second;
}

bool NaturalCertifier::certify(const Box& box) {
  try {
    const Box out = f_.to_output(sub_, box);
    const Chart& c = chart(f_.chart_for(out));
    if (!c.system) return false;
    const Box natural = f_.output_to_natural(f_.chart_for(out), out);
    const newton::Certificate cert = newton::certify_root(*c.system, natural, c.domain, options_);
    return cert.status == newton::Status::certified && cert.unique_in_hull && (c.domain.empty() || cert.root_in_domain);
  } catch (const std::exception&) {  // a box too wide for a chart: not certified, keep searching
    return false;
  }
}

std::unique_ptr<Certifier> NaturalCertifier::clone() const {
  return std::make_unique<NaturalCertifier>(f_, sub_, options_);
}

}  // namespace linkbox::solve
