#pragma once
/// Fitting a dictionary's bounds to a curator's marks ("texture T of object O should / should
/// not be called C"): the bounds of the marked concepts' features that reproduce the marks,
/// moving as few bounds as possible and as little as possible (`geotex dict fit`, the
/// workbench's POST /api/fit; the rule is in docs/words.md, "Fitting bounds to marks").

#include <Eigen/Core>
#include <string>
#include <vector>

#include "annotation/dictionary.hpp"
#include "annotation/dictionary_edit.hpp"
#include "annotation/significance.hpp"

namespace geotex {

/// One mark: texture `texture` of object `object` should (yes) or should not carry `concept_id`.
struct FitMark {
    std::string object;
    int texture = -1;
    std::string concept_id;
    bool yes = true;
    std::string where;  ///< where the mark comes from, for messages ("marks.csv:4"); optional
};

/// What describe_textures needs of one object (as LoadedObject holds it).
struct FitObject {
    std::string id;
    Eigen::MatrixXd features;        ///< #texels by kNumFeatures
    std::vector<int> texel_texture;  ///< #texels
    int num_textures = 0;
    std::vector<DetailOrientation> texture_orientation;  ///< #textures
    DescriptionParams params;                            ///< the word choice of its run
};

/// A mark the fit does not reproduce, and why.
struct FitProblem {
    FitMark mark;
    std::string reason;  ///< one line
};

/// The proposal.
struct DictionaryFitResult {
    /// Bound edits in an order in which edit_dictionary applies them as meant (a bound
    /// shared by two intervals is one edit: edit_dictionary moves both).
    std::vector<DictionaryEdit> edits;
    /// Marks that no placement of the bounds satisfies together with the others (a value
    /// marked yes and no, a texture without a value of the feature, an unknown concept,
    /// object or texture); the fit leaves them out.
    std::vector<FitProblem> unsatisfied;
    /// Marks whose interval the proposal satisfies but that describe_textures still does not
    /// reproduce (the agreement of the texels, the stability, the relief, another feature of
    /// the facet chosen first).
    std::vector<FitProblem> not_reproduced;
    /// The dictionary with the edits applied (its concepts' bounds and bound texts).
    Dictionary fitted;
};

/// Proposes bounds for the features of the marked concepts so that each mark's texture value
/// V (the mean of the feature over the texture's texels, as describe_textures computes it)
/// lies in the concept's interval for yes, outside it for no. Per feature, the bounds keep
/// their order and intervals stay disjoint (a shared bound stays shared, a gap stays a gap
/// or closes); the proposal satisfies as many marks as possible, then moves as few bounds as
/// possible, then as little as possible; a moved bound is the shortest decimal strictly
/// between the neighbouring texture values (of every texture of `objects`) that keeps the
/// marks, the nearest to the old bound among the shortest. Infinite bounds stay. Marks name
/// objects by FitObject::id. Deterministic; never throws on bad marks (they are
/// `unsatisfied`).
DictionaryFitResult fit_dictionary(const Dictionary& dictionary,
                                   const std::vector<FitObject>& objects,
                                   const std::vector<FitMark>& marks);

/// The shortest decimal strictly between `a` and `b` (a < b, either may be infinite but not
/// both), nearest to `target` among the shortest; its text in `text` (no exponent, at most 15
/// significant digits). False when there is none that a double tells apart from a and b.
bool shortest_decimal_between(double a, double b, double target, double& value, std::string& text);

}  // namespace geotex
