#include "studio/studio_server.h"

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "interpreters/output_file.h"
#include "studio/studio_assets.h"

namespace ontogen::studio {

namespace {
constexpr const char* kJson = "application/json";

HttpResponse json(const nlohmann::json& value, int status = 200) { return {status, kJson, value.dump()}; }
HttpResponse error(int status, const std::string& message) { return json({{"error", message}}, status); }

// The body of a POST as a JSON object; nullopt-like: a discarded value when it is none.
nlohmann::json bodyOf(const HttpRequest& request) {
  nlohmann::json body = nlohmann::json::parse(request.body, nullptr, false);
  return body.is_object() ? body : nlohmann::json(nlohmann::json::value_t::discarded);
}
}  // namespace

void StudioServer::idle() {
  const std::lock_guard<std::mutex> lock(mutex_);
  model_.refresh();
}

void StudioServer::restartGallery() {
  // The gallery starts from what the page shows: the text with the sliders' values.
  const VariationSpace space(model_.text());
  Genome genome = space.original();
  const auto values = model_.defineValues();
  for (std::size_t i = 0; i < space.genes().size(); ++i) {
    const Gene& gene = space.genes()[i];
    if (gene.kind != Gene::Kind::Define) continue;
    if (auto value = values.find(gene.name); value != values.end()) genome.values[i] = value->second;
  }
  gallery_.reset(space.programText(genome), model_.stem());
  galleryText_ = model_.text();
}

HttpResponse StudioServer::handle(const HttpRequest& request) {
  const std::string& path = request.path;
  const bool get = request.method == "GET" || request.method == "HEAD";
  const bool post = request.method == "POST";
  try {
    if (get) {
      for (const StudioAsset& asset : studioAssets())
        if (asset.path == path || (path == "/index.html" && asset.path == "/"))
          return {200, std::string(asset.contentType), std::string(asset.bytes)};
      if (path == "/" && studioAssets().empty())
        return {200, "text/plain; charset=utf-8",
                "This build of ontogen has no studio page: it was built without esbuild and three.js (bash .ci/setup "
                "installs them; then build again).\n"};
      const std::lock_guard<std::mutex> lock(mutex_);
      if (path == "/api/state") return json(model_.state());
      if (path == "/model.glb") {
        if (model_.glb().empty()) return error(404, "no model has grown yet (see the diagnostics)");
        return {200, "model/gltf-binary", model_.glb()};
      }
      if (path == "/api/notes") {
        nlohmann::json notes = nlohmann::json::array();
        for (const StudioNote& note : model_.notes())
          notes.push_back({{"start", note.start},
                           {"duration", note.duration},
                           {"channel", note.channel},
                           {"pitch", note.pitch},
                           {"velocity", note.velocity}});
        return json({{"modelVersion", model_.modelVersion()}, {"notes", notes}});
      }
      if (path == "/api/gallery") {
        if (!gallery_.ready() || galleryText_ != model_.text()) restartGallery();
        return json(gallery_.state());
      }
      if (path.starts_with("/gallery/") && path.ends_with(".png")) {
        const std::string number = path.substr(9, path.size() - 13);
        if (number.empty() || number.size() > 3 || number.find_first_not_of("0123456789") != std::string::npos)
          return error(404, "no such picture");
        const std::size_t index = std::stoul(number);
        if (!gallery_.ready() || index >= gallery_.variants().size() || gallery_.variants()[index].png.empty())
          return error(404, "no picture of variant " + number);
        return {200, "image/png", gallery_.variants()[index].png};
      }
      return error(404, "no such page: " + path);
    }
    if (post) {
      const std::lock_guard<std::mutex> lock(mutex_);
      const nlohmann::json body = bodyOf(request);
      if (body.is_discarded()) return error(400, "the request's body is not a JSON object");
      if (path == "/api/define") {
        if (!body.contains("name") || !body["name"].is_string() || !body.contains("value") || !body["value"].is_number())
          return error(400, "a define takes {\"name\": NAME, \"value\": NUMBER}");
        const double value = body["value"].get<double>();
        if (!std::isfinite(value)) return error(400, "a define's value must be finite");
        if (!model_.setDefine(body["name"].get<std::string>(), value))
          return error(422, "the program has no #define " + body["name"].get<std::string>());
        return json(model_.state());
      }
      if (path == "/api/breed") {
        if (!body.contains("picked") || !body["picked"].is_array()) return error(400, "breed takes {\"picked\": [K, ...]}");
        std::vector<int> picked;
        for (const nlohmann::json& k : body["picked"]) {
          if (!k.is_number_integer()) return error(400, "picked variants are whole numbers");
          picked.push_back(k.get<int>());
        }
        if (!gallery_.ready()) restartGallery();
        gallery_.breed(picked);
        return json(gallery_.state());
      }
      if (path == "/api/save") {
        if (!body.contains("index") || !body["index"].is_number_integer()) return error(400, "save takes {\"index\": K}");
        return json({{"path", gallery_.save(body["index"].get<int>()).string()}});
      }
      if (path == "/api/gallery/restart") {
        restartGallery();
        return json(gallery_.state());
      }
      return error(404, "no such action: " + path);
    }
    return error(405, "the studio answers GET and POST");
  } catch (const std::invalid_argument& bad) {
    return error(422, bad.what());
  } catch (const OutputError& failed) {
    return error(500, failed.what());
  } catch (const std::exception& failed) {
    return error(500, std::string("internal error: ") + failed.what());
  }
}

}  // namespace ontogen::studio
