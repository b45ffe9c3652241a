#include "provider/service/service_server.hpp"

#include <utility>

#include "provider/content/download_route.hpp"
#include "provider/discovery/nearby_routes.hpp"
#include "provider/put/upload_route.hpp"
#include "provider/service/site_route.hpp"

namespace umf::provider {

namespace http = boost::beast::http;

std::shared_ptr<const HttpRoutes> make_http_routes(std::shared_ptr<const Service> service) {
    auto routes = std::make_shared<HttpRoutes>();
    // Any method: a method other than PUT is refused by the upload itself.
    routes->on_header.add_prefix(kUploadPrefix,
                                 [service](HttpExchange& exchange, http::request_parser<http::empty_body>&& header) {
                                     serve_upload(exchange, std::move(header), service->puts());
                                 });
    routes->on_header.add_path(
        kSharePath, [](HttpExchange& exchange, http::request_parser<http::empty_body>&&) { answer_share(exchange); },
        {http::verb::post});

    const RouteTable<RequestRoute>::Methods get_or_head{http::verb::get, http::verb::head};
    routes->on_request.add_prefix(
        kDownloadPrefix,
        [service](HttpExchange& exchange, const HttpRequest& req) {
            serve_download(exchange, req, service->downloads(),
                           [service](const std::filesystem::path& file) { service->forget_file(file); });
        },
        get_or_head);
    routes->on_request.add_path(
        kNearbyPath,
        [service](HttpExchange& exchange, const HttpRequest& req) {
            serve_nearby(exchange, req, service->config().nearby.get());
        },
        get_or_head);
    routes->on_request.add_path(
        kFieldPath,
        [service](HttpExchange& exchange, const HttpRequest& req) { serve_field(exchange, req, service->screens()->field); },
        get_or_head);
    routes->on_request.add_prefix(
        "", [service](HttpExchange& exchange, const HttpRequest& req) { serve_site(exchange, req, service->site()); },
        get_or_head);
    return routes;
}

std::unique_ptr<Server> make_server(std::shared_ptr<const Service> service, const TlsIdentity& identity,
                                    ServerOptions options) {
    auto routes = make_http_routes(service);
    return std::make_unique<Server>(std::move(service), std::move(routes), identity, std::move(options));
}

}  // namespace umf::provider
