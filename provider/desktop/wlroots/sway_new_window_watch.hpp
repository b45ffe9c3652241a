// Placing a put's window on Sway: the views there before the opener starts
// are remembered; then GET_TREE is polled for a new one (preferably of the
// opener's process tree), which is made floating and moved so that its
// frame is centred on the pointed place, kept on the output.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "provider/desktop/desktop.hpp"

namespace umf::provider {

class SwayNewWindowWatch final : public NewWindowWatch {
public:
    // nullptr when sway does not answer.
    static std::unique_ptr<SwayNewWindowWatch> create(std::string swaysock, WindowPlacement where);
    std::optional<unsigned long> place(int child_pid, std::chrono::milliseconds wait) override;

private:
    SwayNewWindowWatch(std::string swaysock, WindowPlacement where, std::vector<unsigned long> before);
    // Floats it and moves it; false when sway refused.
    bool move(unsigned long id) const;

    std::string swaysock_;
    WindowPlacement where_;
    std::vector<unsigned long> before_;
};

}  // namespace umf::provider
