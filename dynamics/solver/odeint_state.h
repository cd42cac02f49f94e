#pragma once
/// @file
/// Internal to the solver: Boost.Odeint sizes its scratch states like the state it is given
/// (a TrainState holds 4 + 2(N − 1) entries of its inline capacity; odeint's default resize
/// and size comparison use its resize() and Boost.Range size).

#include <boost/numeric/odeint/util/is_resizeable.hpp>
#include <boost/type_traits/integral_constant.hpp>

#include "dynamics/model/needle_train.h"

namespace boost {
namespace numeric {
namespace odeint {

template <>
struct is_resizeable<needle::TrainState> {
  typedef boost::true_type type;
  static const bool value = type::value;
};

}  // namespace odeint
}  // namespace numeric
}  // namespace boost
