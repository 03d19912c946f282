#pragma once
// Analysis of variance for factorial and orthogonal-array designs.
//
// Each term (a main effect or an interaction of factors) owns a space of contrasts: for a factor
// with L levels the L - 1 centred level indicators, for an interaction the products of its
// factors' contrasts. The term's sum of squares is the squared length of the projection of the
// response onto that space, its degrees of freedom the dimension of the space. For balanced
// designs this equals the textbook formulas (SS_A = sum_l n_l (ybar_l - ybar)^2, interactions
// by cell means) and the term spaces are mutually orthogonal, so the sums of squares add up to
// the total. The function checks that orthogonality and refuses designs where terms are aliased
// or partially confounded (a fractional design asked for an interaction it cannot separate),
// because the decomposition would then double-count variation.
//
// Error: the residual (total minus all terms), which in a replicated factorial is pure error.
// Saturated designs (an L9 with four factors, a PB-12 with eleven) leave no residual; pool the
// terms judged negligible (usually the smallest sums of squares) into the error with
// `AnovaOptions::pooled`. Without error degrees of freedom F and p are NaN.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

struct AnovaTerm {
  std::vector<int> factors;  // design columns; one = main effect, more = interaction
};

struct AnovaOptions {
  // Factor names; default A, B, C, ... Interaction names join them with '*'.
  std::vector<std::string> factor_names;
  // Terms to analyse; empty = every main effect.
  std::vector<AnovaTerm> terms;
  // Indices into the term list whose sums of squares and degrees of freedom join the error.
  std::vector<int> pooled;
};

struct AnovaRow {
  std::string name;
  double ss = 0;  // sum of squares
  int df = 0;     // degrees of freedom
  double ms = 0;  // mean square ss / df
  double f = 0;   // ms / ms_error (NaN if pooled or no error df)
  double p = 0;   // upper tail of F(df, df_error) at f
  bool pooled = false;
};

struct AnovaTable {
  std::vector<AnovaRow> terms;  // in the order requested, pooled ones flagged
  AnovaRow error;               // residual + pooled terms
  AnovaRow total;               // corrected total, df = runs - 1
  int residual_df = 0;          // error df before pooling
  std::string note;             // why F/p are missing, if they are
  std::string format() const;
};

// All main effects and interactions of up to `max_order` of k factors, in standard (Yates) order:
// A, B, AB, C, AC, BC, ABC, D, ...
std::vector<AnovaTerm> factorial_terms(int k, int max_order);

// design: runs x factors (coded or natural; levels are the distinct values of each column),
// y: one response per run. Throws std::invalid_argument for empty or mismatched input, unknown
// factor indices, and non-orthogonal terms.
AnovaTable anova(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                 const AnovaOptions& options = {});

}  // namespace cdem::calib
