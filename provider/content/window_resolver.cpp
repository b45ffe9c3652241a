#include "provider/content/window_resolver.hpp"

#include <stdexcept>

#include "provider/content/file_facts.hpp"
#include "shared/protocol/messages.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

WindowResolver::WindowResolver(std::shared_ptr<const Desktop> desktop, WindowResolverOptions options)
    : desktop_(std::move(desktop)), options_(std::move(options)), recent_files_(options_.recent_files) {
    if (!desktop_) throw std::invalid_argument("WindowResolver: no desktop");
}

std::optional<WindowInfo> WindowResolver::window_at(double x, double y) const {
    return desktop_->window_at(x, y, options_.filter);
}

std::optional<fs::path> WindowResolver::document_of(const WindowInfo& window) const {
    const auto documents = process_documents(window.pid, options_.documents);
    if (documents.size() == 1) return documents.front();
    for (const auto& document : documents)
        if (title_mentions(window.title, document.filename().string())) return document;
    if (options_.recent_files.empty()) return std::nullopt;
    return match_by_title(*recent_files_.entries(), window.title);
}

std::optional<Resolved> WindowResolver::resolve(const ScreenPoint& point, Purpose) const {
    const auto window = window_at(point.root_x, point.root_y);
    if (!window) return std::nullopt;
    const auto document = document_of(*window);
    if (!document) return std::nullopt;
    Resolved resolved;
    resolved.kind = protocol::ContentKind::file;
    resolved.file = *document;
    resolved.name = protocol::safe_file_name(document->filename().string());
    resolved.mime = mime_for(*document);
    resolved.title = window->title.empty() ? resolved.name : window->title;
    return resolved;
}

}  // namespace umf::provider
