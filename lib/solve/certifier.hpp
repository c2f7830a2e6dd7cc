#pragma once
// Certification during the search: a box that the contractors say holds at most one root is
// handed to a Certifier; when it proves exactly one root, the box is a solution right away,
// whatever its width, and is not refined further.
#include "formulate/formulation.hpp"
#include "newton/certify.hpp"

#include <map>
#include <memory>
#include <optional>

namespace linkbox::solve {

class Certifier {
 public:
  virtual ~Certifier() = default;
  // True only when proved: the box's roots are exactly one root of the case, certified.
  virtual bool certify(const Box& box) = 0;
  virtual std::unique_ptr<Certifier> clone() const = 0;
};

// In the formulation's natural system (verify/ certifies in the same one): the box of
// sub-problem `sub` is mapped to the output variables and to the natural unknowns of its
// chart, where interval Newton must prove a unique root, unique over the whole mapped box,
// inside the domain. Every root of the sub-problem in the box maps into that box, so the
// box holds no other root.
class NaturalCertifier final : public Certifier {
 public:
  NaturalCertifier(const formulate::Formulation& f, size_t sub, newton::NewtonOptions options = {});
  bool certify(const Box& box) override;
  std::unique_ptr<Certifier> clone() const override;

 private:
  const formulate::Formulation& f_;
  size_t sub_;
  newton::NewtonOptions options_;
  // Per chart, built once: the natural system (empty when it is not square) and its domain.
  struct Chart {
    std::optional<newton::SquareSystem> system;
    Box domain;
  };
  const Chart& chart(std::uint64_t c);
  std::map<std::uint64_t, Chart> charts_;  // per instance: not shared between threads
};

}  // namespace linkbox::solve
