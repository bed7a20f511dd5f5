#include "studio/studio_server.h"

#include <cmath>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "interpreters/output_file.h"
#include "studio/request_guard.h"
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


// Where index.html takes the run's token (<meta name="ontogen-token">), which the page's
// script sends back with each change.
constexpr std::string_view kTokenPlaceholder = "ONTOGEN-PAGE-TOKEN";
}  // namespace

StudioServer::StudioServer(StudioModel& model, Gallery& gallery, StudioServerDef def)
    : model_(model),
      gallery_(gallery),
      token_(def.token.empty() ? randomToken() : std::move(def.token)),
      grower_(gallery) {
  for (const StudioAsset& asset : studioAssets()) {
    if (asset.path != "/") continue;
    page_ = std::string(asset.bytes);
    for (std::size_t at; (at = page_.find(kTokenPlaceholder)) != std::string::npos;)
      page_.replace(at, kTokenPlaceholder.size(), token_);
  }
}

void StudioServer::idle() { model_.refresh(); }

HttpResponse StudioServer::events() {
  // Each change of the model's state is one event with the whole state (the growth in
  // progress included); between them a comment every half second finds a page gone away.
  HttpResponse response{200, "text/event-stream", ""};
  response.stream = [this, seen = ~uint64_t{0}](std::string& chunk) mutable {
    const uint64_t now = model_.waitForChange(seen, std::chrono::milliseconds(500));
    if (now == seen) {
      chunk = ":\n\n";
      return true;
    }
    seen = now;
    chunk = "data: " + model_.state().dump() + "\n\n";
    return true;
  };
  return response;
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
  gallery_.setLimits(model_.limits());
  gallery_.reset(space.programText(genome), model_.stem());
  galleryText_ = model_.text();
  grower_.wake();
}

HttpResponse StudioServer::handle(const HttpRequest& request) {
  const std::string& path = request.path;
  const bool get = request.method == "GET" || request.method == "HEAD";
  const bool post = request.method == "POST";
  if (const std::string refusal = refusalOf(request, request.port, token_); !refusal.empty())
    return error(403, refusal);
  try {
    if (get) {
      for (const StudioAsset& asset : studioAssets())
        if (asset.path == path || (path == "/index.html" && asset.path == "/"))
          return {200, std::string(asset.contentType), asset.path == "/" ? page_ : std::string(asset.bytes)};
      if (path == "/" && studioAssets().empty())
        return {200, "text/plain; charset=utf-8",
                "This build of ontogen has no studio page: it was built without esbuild and three.js (bash .ci/setup "
                "installs them; then build again).\n"};
      if (path == "/api/state") return json(model_.state());
      if (path == "/api/events") return events();
      if (path == "/model.glb") {
        std::string glb = model_.glb();
        if (glb.empty()) return error(404, "no model has grown yet (see the diagnostics)");
        return {200, "model/gltf-binary", std::move(glb)};
      }
      if (path.starts_with("/model/picture/") && path.ends_with(".png")) {
        const std::string number = path.substr(15, path.size() - 19);
        if (number.empty() || number.size() > 6 || number.find_first_not_of("0123456789") != std::string::npos)
          return error(404, "no such picture");
        std::string png = model_.picture(std::stoul(number));
        if (png.empty()) return error(404, "the model has no picture of frame " + number);
        return {200, "image/png", std::move(png)};
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
      const auto lock = grower_.lock();
      if (path == "/api/gallery") return json(gallery_.state());
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
      const nlohmann::json body = bodyOf(request);
      if (body.is_discarded()) return error(400, "the request's body is not a JSON object");
      if (path == "/api/define") {
        if (!body.contains("name") || !body["name"].is_string() || !body.contains("value") || !body["value"].is_number())
          return error(400, "a define takes {\"name\": NAME, \"value\": NUMBER}");
        const double value = body["value"].get<double>();
        if (!std::isfinite(value)) return error(400, "a define's value must be finite");
        model_.setDefine(body["name"].get<std::string>(), value);  // 422 when unknown or out of range
        model_.requestGrowth();
        return json(model_.state());
      }
      if (path == "/api/define/write" || path == "/api/define/drop") {
        if (body.size() != 1 || !body.contains("name") || !body["name"].is_string())
          return error(400, "writing or dropping a define takes {\"name\": NAME}");
        const std::string name = body["name"].get<std::string>();
        nlohmann::json answer;
        if (path == "/api/define/write") answer["path"] = model_.writeDefine(name);  // 422 when it cannot
        else model_.dropDefine(name);
        model_.requestGrowth();
        answer["state"] = model_.state();
        return json(answer);
      }
      if (path == "/api/stop") {
        model_.stop();
        return json(model_.state());
      }
      if (path == "/api/limits") {
        if (!body.contains("maxCells") || !body["maxCells"].is_number_unsigned() || !body.contains("maxMemoryMiB") ||
            !body["maxMemoryMiB"].is_number_unsigned() || body["maxMemoryMiB"].get<uint64_t>() > (uint64_t{1} << 40))
          return error(400, "limits take {\"maxCells\": N, \"maxMemoryMiB\": M}");
        model_.setLimits(body["maxCells"].get<uint64_t>(), body["maxMemoryMiB"].get<uint64_t>() << 20);
        model_.requestGrowth();
        // The gallery's variants to come grow within the page's limits too.
        const auto lock = grower_.lock();
        gallery_.setLimits(model_.limits());
        return json(model_.state());
      }
      const auto lock = grower_.lock();
      if (path == "/api/gallery") {
        if (!gallery_.ready() || galleryText_ != model_.text()) restartGallery();
        return json(gallery_.state());
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
        grower_.wake();
        return json(gallery_.state());
      }
      if (path == "/api/save") {
        // The studio names the file (studio/gallery.h): a request picks a variant, never a
        // name or a folder.
        if (body.size() != 1 || !body.contains("index") || !body["index"].is_number_integer())
          return error(400, "save takes {\"index\": K} alone: the studio names the file it writes");
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
