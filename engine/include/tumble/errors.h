// The two ways the engine refuses to go on: a scene that is not valid, and a
// simulation whose state stopped making sense.
#pragma once

#include <stdexcept>
#include <string>

namespace tumble {

/// A scene value that is wrong. `path` names the field, e.g. "bodies[2].shape.radius".
class SceneError : public std::runtime_error {
public:
    SceneError(std::string path, const std::string& message)
        : std::runtime_error(path.empty() ? message : path + ": " + message),
          path_(std::move(path)), message_(message) {}
    const std::string& path() const { return path_; }
    const std::string& message() const { return message_; }

private:
    std::string path_;
    std::string message_;
};

/// The state became non-finite (or otherwise unusable) during a run.
class SimulationError : public std::runtime_error {
public:
    SimulationError(int body, std::string bodyName, double time, const std::string& what)
        : std::runtime_error(what), body_(body), bodyName_(std::move(bodyName)), time_(time) {}
    int body() const { return body_; }
    const std::string& bodyName() const { return bodyName_; }
    double time() const { return time_; }

private:
    int body_;
    std::string bodyName_;
    double time_;
};

}  // namespace tumble
