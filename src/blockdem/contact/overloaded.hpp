// Overloaded{f, g, ...}: one callable from several lambdas, for exhaustive std::visit over the law
// variants (a law without a case does not compile).
#pragma once

namespace blockdem {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace blockdem
