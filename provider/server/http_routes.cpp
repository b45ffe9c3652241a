#include "server/http_routes.hpp"

#include "content/download_route.hpp"
#include "discovery/nearby_routes.hpp"
#include "put/upload_route.hpp"
#include "server/http_session.hpp"
#include "server/site_route.hpp"

namespace umf::provider {

namespace http = boost::beast::http;

std::shared_ptr<const HttpRoutes> make_http_routes(std::shared_ptr<const Service> service) {
    auto routes = std::make_shared<HttpRoutes>();
    // Any method: a method other than PUT is refused by the upload itself.
    routes->on_header.add_prefix(kUploadPrefix,
                                 [service](HttpSession& session, http::request_parser<http::empty_body>&& header) {
                                     serve_upload(session, std::move(header), service->puts());
                                 });
    routes->on_header.add_path(
        kSharePath, [](HttpSession& session, http::request_parser<http::empty_body>&&) { answer_share(session); },
        {http::verb::post});

    const RouteTable<RequestRoute>::Methods get_or_head{http::verb::get, http::verb::head};
    // Any method: each API path says which one it takes.
    routes->on_request.add_prefix(kApiPrefix,
                                  [](HttpSession& session, const HttpRequest& req) { session.serve_api(req); });
    routes->on_request.add_prefix(
        kDownloadPrefix,
        [service](HttpSession& session, const HttpRequest& req) {
            serve_download(session, req, service->downloads(),
                           [service](const std::filesystem::path& file) { service->forget_file(file); });
        },
        get_or_head);
    routes->on_request.add_path(
        kNearbyPath,
        [service](HttpSession& session, const HttpRequest& req) {
            serve_nearby(session, req, service->config().nearby.get());
        },
        get_or_head);
    routes->on_request.add_path(
        kFieldPath,
        [service](HttpSession& session, const HttpRequest& req) { serve_field(session, req, service->screens()->field); },
        get_or_head);
    routes->on_request.add_prefix(
        "", [service](HttpSession& session, const HttpRequest& req) { serve_site(session, req, service->site()); },
        get_or_head);
    return routes;
}

}  // namespace umf::provider
