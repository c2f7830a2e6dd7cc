#pragma once
// An infinite domain bound is refused by every reader with the same advice: linkbox encloses
// roots in a bounded box only, and a change of variables onto a bounded interval would make
// the certificates speak of another system, so the message suggests a finite bound rather
// than inventing one.
#include <string>

namespace linkbox::input {

// "linkbox encloses roots ... e.g. [-1000, 1000]: ..." for a domain whose lower and/or upper
// end is infinite; the suggestion is a power of ten beyond the finite end's magnitude.
std::string unbounded_domain_advice(bool lower_infinite, bool upper_infinite, double finite_magnitude);

}  // namespace linkbox::input
