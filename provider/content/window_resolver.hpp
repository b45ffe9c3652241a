// The window under a screen point and the document it shows (docs/
// ARCHITECTURE.md, "Content", resolver 3), for every desktop backend: the
// window from the desktop (desktop/desktop.hpp), the document from the
// window's process (process_documents.hpp) or from the recently used files
// matched by the window's title (recent_files.hpp).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "provider/content/process_documents.hpp"
#include "provider/content/recent_files.hpp"
#include "provider/content/resolver.hpp"
#include "provider/desktop/desktop.hpp"

namespace umf::provider {

struct WindowResolverOptions {
    WindowFilter filter;  // give own_pids at least getpid()
    ProcessDocumentOptions documents;
    std::filesystem::path recent_files = default_recent_files_path();  // empty: not consulted
};

// Kind file: the document of the window under the point. nullopt when the
// point is on no window or the window's document is unknown (the snapshot
// resolver answers then).
class WindowResolver final : public Resolver {
public:
    WindowResolver(std::shared_ptr<const Desktop> desktop, WindowResolverOptions options = {});
    const char* name() const override { return "window"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

    // In desktop coordinates.
    std::optional<WindowInfo> window_at(double x, double y) const;
    // The process's document when there is one, or the one of several the
    // title names; else the recently used file the title names.
    std::optional<std::filesystem::path> document_of(const WindowInfo& window) const;

private:
    std::shared_ptr<const Desktop> desktop_;
    WindowResolverOptions options_;
    RecentFilesCache recent_files_;
};

}  // namespace umf::provider
