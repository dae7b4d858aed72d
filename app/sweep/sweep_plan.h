// The variants of a sweep (`tumble sweep`, docs/sweeps.md): the values each `--vary` gives
// one value of the scene, their full product, and each variant written as a scene file of
// its own that `tumble --headless` runs by itself.
//
// A path names a value of the scene as the file holds it, normalised (every body key
// written out, so that `ball.velocity[1]` exists even where the file leaves the velocity
// at its default): the first part is `settings`, a body's name or a joint's name, then keys
// and [index]es, e.g. `ball.restitution`, `ball.shape.radius`, `settings.gravity[1]`.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tumble::sweep {

/// Bad input to a sweep (an unknown path, an empty or malformed list): exit status 2.
struct SweepError {
    std::string message;
};

/// One `--vary PATH=VALUES`. VALUES is `a,b,c` or `start:stop:count` (both ends included,
/// evenly spaced); the values are kept as text (numbers in their shortest exact form), the
/// way the summary's column shows them.
struct Vary {
    std::string path;
    std::vector<std::string> values;
};

/// Parses "PATH=VALUES" (the path is checked against a scene by makePlan). Throws SweepError.
Vary parseVary(const std::string& text);

/// A sweep: the scene, what varies, and the variants (the product of the values, the last
/// `--vary` changing fastest).
struct Plan {
    std::filesystem::path scene;  // absolute
    std::vector<Vary> vary;
    int count = 0;
    std::vector<std::string> bodies;  // the scene's dynamic bodies, whose measures a run gives
    /// A hash of the scene's content as planned (normalised): a resumed sweep whose scene
    /// was edited since is refused. Empty in a plan of a sweep made before it was kept.
    std::string sceneHash;
    /// The value index of each `--vary` in variant k.
    std::vector<int> choice(int k) const;
    /// Variant k's name: its number, zero-padded to 4 digits (or as many as the last needs).
    std::string name(int k) const;
};

/// Reads the scene (throws SweepError with the reader's message on a bad file), checks
/// every path against it and the values against the kind of value there (a number, a
/// whole number, true/false, a word), and returns the plan. Nothing is written.
Plan makePlan(const std::filesystem::path& scene, const std::vector<Vary>& vary);

/// Writes DIR/sweep.json (the plan, so that `--merge DIR` and a resumed sweep know it) and
/// DIR/variants/NAME.json for every variant, each written whole or not at all. Every variant
/// is read and checked first: one the scene format refuses (a restitution of 1.5, a dt of
/// 0) throws SweepError naming it and the field, and nothing is written. A DIR that holds
/// another sweep (its sweep.json differs), or this sweep of a scene edited since, throws
/// SweepError: nothing is overwritten. Returns a line ("0003: ...", tumble::stepNote) for each
/// variant whose step is not its dt.
/// `stopped` (Ctrl-C) is asked between variants: when it says so, SweepStopped is thrown
/// and what was written stays whole (each file written whole or not at all; a resume
/// writes the rest).
std::vector<std::string> writeVariants(const Plan& plan, const std::filesystem::path& dir,
                                       const std::function<bool()>& stopped = {});

/// writeVariants was stopped.
struct SweepStopped {};

/// The plan a sweep folder holds (its sweep.json). Throws SweepError when there is none or
/// it cannot be read.
Plan readPlan(const std::filesystem::path& dir);

/// Where variant k's scene file is.
std::filesystem::path variantFile(const Plan& plan, const std::filesystem::path& dir, int k);

/// The value `path` names in variant k's scene file, as text the way a --vary value is
/// shown (numbers in their shortest exact form), for a merged summary's column of a path
/// this sweep did not vary. "" when the file or the place is missing; "mixed" when a
/// wildcard path finds different values.
std::string valueInVariant(const Plan& plan, const std::filesystem::path& dir, int k,
                           const std::string& path);

}  // namespace tumble::sweep
