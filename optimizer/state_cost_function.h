// A one-sample cost term as a Ceres cost function, differentiated through the sample's state instead of
// through its 32 knot values (docs/optimize.md, "Speed").
//
// A sample's state (optimizer/sample_model.h) is linear in its four knots: each field is a blend of one
// channel of the four knots, with the spline's value, first, second or third derivative weights. So the
// Jacobian of a term in knot j, channel c, is the chain rule
//   dr/dk_j[c] = value_j dr/dvalue_c + d1_j dr/drate_c + d2_j dr/daccel_c + d3_j dr/djerk_c,
// and automatic differentiation only has to run over the state's fields the term reads: the eight
// channel values (kValues) for the framing, depth of field, keep-out, occlusion and team terms, and
// with them the eight first derivatives and the path's acceleration and jerk (kValuesAndRates, 22) for
// the limits, whose active hinges, as hinges (`rows` below), give their gradients in those 22 fields
// themselves (LimitsCost::ActiveGradients, no Jets), as do the goals (framing, depth of field, background
// blur: their Gradients, in the eight channel values). The residuals are the same numbers as with
// `ceres::AutoDiffCostFunction` over the knots (the state is evaluated by the same code), only the
// Jacobian's rounding differs.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/cost_function.h>
#include <ceres/jet.h>

#include "optimizer/sample_model.h"

namespace cinepath::optimizer {

enum StateFields { kValues = kNumChannels, kValuesAndRates = 2 * kNumChannels + 6 };

// The derivatives of a term's rows in its sample's state, one row of kValuesAndRates per residual: the
// eight channel values, their eight first derivatives, then the path's acceleration and jerk (east, north,
// up), as StateCostFunction::Seeded numbers them; zero where the term does not read a field.
inline constexpr int kStateFields = kValuesAndRates;

// The chain rule from a block's state rows to its four knots (the Jacobians as ceres::CostFunction gives them).
inline void StateRowsToKnots(const KnotWeights& w, const double* state_rows, int rows, double** jacobians) {
  for (int j = 0; j < 4; ++j) {
    if (!jacobians[j]) continue;
    for (int i = 0; i < rows; ++i) {
      const double* d = state_rows + i * kStateFields;
      double* row = jacobians[j] + i * kNumChannels;
      for (int c = 0; c < kNumChannels; ++c) {
        row[c] = w.value[j] * d[c] + w.d1[j] * d[kNumChannels + c];
        if (c < 3) row[c] += w.d2[j] * d[2 * kNumChannels + c] + w.d3[j] * d[2 * kNumChannels + 3 + c];
      }
    }
  }
}

// A one-sample term evaluated at its sample's state, already computed: the Jacobian in the four knots as
// `ceres::CostFunction::Evaluate` gives it (optimizer/sample_cost_function.h stacks a sample's terms in one
// residual block and evaluates the state once for all of them), or in the state's fields (`state_rows`:
// rows x kStateFields, null for the residuals only), which the banded solver (optimizer/banded_solver.h)
// takes through the spline's weights itself.
class StatePart {
 public:
  virtual ~StatePart() = default;
  virtual bool EvaluateState(const SampleState<double>& s, double* residuals, double* state_rows) const = 0;
  virtual int rows() const = 0;
  bool EvaluateAt(const SampleState<double>& s, double* residuals, double** jacobians, const KnotWeights& w) const {
    if (!jacobians) return EvaluateState(s, residuals, nullptr);
    double state_rows[kMaxStateRows * kStateFields];
    if (!EvaluateState(s, residuals, state_rows)) return false;
    StateRowsToKnots(w, state_rows, rows(), jacobians);
    return true;
  }
  static constexpr int kMaxStateRows = 19;
};

// A block of residuals on one sample's four knots that can give its Jacobian in the sample's state (the
// sample blocks, and the one-sample terms in blocks of their own): the banded solver asks for that.
class StateBlock {
 public:
  virtual ~StateBlock() = default;
  virtual bool EvaluateStateBlock(double const* const* parameters, double* residuals, double* state_rows) const = 0;
  virtual const KnotWeights& knot_weights() const = 0;
};

// A functor of hinges that writes the gradients of its active ones itself (LimitsCost::ActiveGradients).
template <typename Functor>
concept AnalyticHinges = requires(const Functor& f, const SampleState<double>& s, const bool* only,
                                  double (*g)[kValuesAndRates]) {
  f.ActiveGradients(s, only, g);
};

// A functor that writes its residuals and their gradients in the eight channel values itself (the goals:
// FramingCost::Gradients, SharpCost's, BackgroundBlurCost's), without Jets.
template <typename Functor>
concept AnalyticValueGradients = requires(const Functor& f, const SampleState<double>& s, double* r,
                                          double (*g)[kNumChannels]) {
  f.Gradients(s, r, g);
};

// Functor: has `base` (SampleBase) and `template <T> bool Residuals(const SampleState<T>&, T*) const`
// that reads only the fields `kFields` seeds. Owns the functor.
//
// Hinges (the limits): `rows` > 0 says every residual is a hinge, max(0, x): where all are zero, so are
// their derivatives, and nothing is differentiated; else a functor with AnalyticHinges gives the active
// ones' gradients itself, and any other runs its Jets. `rows` < the
// functor's `residuals` passes only the nonzero residuals, in order, in `rows` rows (zeros after them), and when more
// are nonzero, the square root of the sum of the squares of the rest in the last row. The cost is the same sum of
// squares; the Gauss-Newton model is the same while no more than `rows` hinges of the sample are active (almost always:
// a sample rarely presses on more than two limits at once), and every Jacobian product of the solve handles `rows` rows
// instead of 19, most of them zero.
template <typename Functor, int kFields>
class StateCostFunction : public ceres::CostFunction, public StatePart, public StateBlock {
 public:
  static constexpr int kMaxResiduals = 19;
  StateCostFunction(Functor* functor, int residuals, int rows = 0)
      : functor_(functor), functor_rows_(residuals), hinges_(rows > 0) {
    set_num_residuals(rows > 0 && rows < residuals ? rows : residuals);
    for (int j = 0; j < 4; ++j) mutable_parameter_block_sizes()->push_back(kNumChannels);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return EvaluateAt(EvaluateSample(functor_->base, parameters), residuals, jacobians, functor_->base.knots);
  }
  bool EvaluateStateBlock(double const* const* parameters, double* residuals, double* state_rows) const override {
    return EvaluateState(EvaluateSample(functor_->base, parameters), residuals, state_rows);
  }
  const KnotWeights& knot_weights() const override { return functor_->base.knots; }
  int rows() const override { return num_residuals(); }
  bool EvaluateState(const SampleState<double>& s, double* residuals, double* state_rows) const override {
    if (!state_rows || hinges_) {
      double full_values[kMaxResiduals];
      if (!functor_->Residuals(s, full_values)) return false;
      Compact(full_values, residuals);
      if (!state_rows) return true;
      // Every hinge inactive: zero residuals, and zero derivatives (max(0, x) is flat at x <= 0).
      if (std::all_of(residuals, residuals + num_residuals(), [](double r) { return r == 0.0; })) {
        std::fill(state_rows, state_rows + num_residuals() * kStateFields, 0.0);
        return true;
      }
      if constexpr (kFields == kValuesAndRates && AnalyticHinges<Functor>) {
        bool active[kMaxResiduals];  // the hinges nonzero at s, the only ones differentiated
        for (int i = 0; i < functor_rows_; ++i) active[i] = full_values[i] != 0.0;
        if (hinges_) return HingeRows(s, full_values, active, residuals, state_rows);
      }
    }
    if constexpr (kFields == kValues && AnalyticValueGradients<Functor>) {
      if (!hinges_ && num_residuals() == functor_rows_) {
        double g[kMaxResiduals][kNumChannels];
        functor_->Gradients(s, residuals, g);
        for (int i = 0; i < num_residuals(); ++i) {
          double* row = state_rows + i * kStateFields;
          std::copy(g[i], g[i] + kNumChannels, row);
          std::fill(row + kNumChannels, row + kStateFields, 0.0);
        }
        return true;
      }
    }
    using Jet = ceres::Jet<double, kFields>;
    Jet full[kMaxResiduals], r[kMaxResiduals];
    if (!functor_->Residuals(Seeded<Jet>(s), full)) return false;
    Compact(full, r);
    for (int i = 0; i < num_residuals(); ++i) {
      residuals[i] = r[i].a;
      double* row = state_rows + i * kStateFields;
      for (int f = 0; f < kStateFields; ++f) row[f] = f < kFields ? r[i].v[f] : 0.0;
    }
    return true;
  }

 private:
  // The hinges' state rows from the functor's own gradients of the active ones, without Jets: each row's
  // gradient as Compact picks its value, the last row's, when it lumps the rest, sum(r_i g_i) / its value.
  bool HingeRows(const SampleState<double>& s, const double* full, const bool* active, const double* residuals,
                 double* state_rows) const {
    double g[kMaxResiduals][kValuesAndRates];
    functor_->ActiveGradients(s, active, g);
    const int rows = num_residuals();
    const double* row_gradient[kMaxResiduals] = {};  // null: a zero row
    double lumped[kValuesAndRates] = {};
    if (rows == functor_rows_) {
      for (int i = 0; i < rows; ++i) row_gradient[i] = active[i] ? g[i] : nullptr;
    } else {
      int count = 0;
      for (int i = 0; i < functor_rows_; ++i) {
        if (!active[i]) continue;
        if (count < rows) row_gradient[count] = g[i];
        if (count >= rows - 1) {
          for (int f = 0; f < kValuesAndRates; ++f) lumped[f] += full[i] * g[i][f];
        }
        ++count;
      }
      if (count > rows) {
        for (double& f : lumped) f /= residuals[rows - 1];
        row_gradient[rows - 1] = lumped;
      }
    }
    for (int i = 0; i < rows; ++i) {
      double* row = state_rows + i * kStateFields;
      if (row_gradient[i]) {
        std::copy(row_gradient[i], row_gradient[i] + kStateFields, row);
      } else {
        std::fill(row, row + kStateFields, 0.0);
      }
    }
    return true;
  }

  // The functor's residuals as the problem's rows (above).
  template <typename T>
  void Compact(const T* full, T* out) const {
    const int rows = num_residuals();
    if (rows == functor_rows_) {
      std::copy(full, full + rows, out);
      return;
    }
    int nonzero[kMaxResiduals], count = 0;
    double largest = 0;  // of the rest's magnitudes, to keep their squares in range
    for (int i = 0; i < functor_rows_; ++i) {
      if (!(full[i] != T(0.0))) continue;
      if (count >= rows - 1) largest = std::max(largest, std::fabs(Value(full[i])));
      nonzero[count++] = i;
    }
    for (int i = 0; i < rows; ++i) out[i] = i < count ? full[nonzero[i]] : T(0.0);
    if (count <= rows) return;
    using std::sqrt;
    T rest(0.0);
    for (int i = rows - 1; i < count; ++i) {
      const T scaled = full[nonzero[i]] / largest;
      rest = rest + scaled * scaled;
    }
    out[rows - 1] = largest * sqrt(rest);
  }
  static double Value(double x) { return x; }
  template <typename Jet>
  static double Value(const Jet& x) {
    return x.a;
  }

  // The state with each field the term reads as an independent variable.
  template <typename Jet>
  static SampleState<Jet> Seeded(const SampleState<double>& s) {
    const auto seed = [](double value, int field) { return field < kFields ? Jet(value, field) : Jet(value); };
    SampleState<Jet> out;
    for (int c = 0; c < 3; ++c) {
      out.position[c] = seed(s.position[c], c);
      out.velocity[c] = seed(s.velocity[c], kNumChannels + c);
      out.acceleration[c] = seed(s.acceleration[c], 2 * kNumChannels + c);
      out.jerk[c] = seed(s.jerk[c], 2 * kNumChannels + 3 + c);
    }
    out.yaw = seed(s.yaw, kYaw);
    out.tilt = seed(s.tilt, kTilt);
    out.log_focal = seed(s.log_focal, kLogFocal);
    out.dioptre = seed(s.dioptre, kDioptre);
    out.stops = seed(s.stops, kStops);
    out.yaw_rate = seed(s.yaw_rate, kNumChannels + kYaw);
    out.tilt_rate = seed(s.tilt_rate, kNumChannels + kTilt);
    out.log_focal_rate = seed(s.log_focal_rate, kNumChannels + kLogFocal);
    out.dioptre_rate = seed(s.dioptre_rate, kNumChannels + kDioptre);
    out.stops_rate = seed(s.stops_rate, kNumChannels + kStops);
    return out;
  }

  std::unique_ptr<Functor> functor_;
  int functor_rows_;
  bool hinges_;  // every residual a hinge, zero with zero derivatives where inactive
};

}  // namespace cinepath::optimizer
