#include "common/scene_loader_document.h"

#include <yaml-cpp/eventhandler.h>

#include <sstream>
#include <vector>

#include "common/scene_loader_node.h"

namespace zonesim {
namespace {

// Records where each document starts and ignores the rest of the events.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> marks;

  void OnDocumentStart(const YAML::Mark& mark) override { marks.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

int lineOf(const YAML::Mark& mark) {
  return mark.is_null() ? 0 : mark.line + 1;
}

// Counts documents, at most three. YAML::LoadAll cannot be used: yaml-cpp 0.7 never consumes a
// stray ',' at block level and reports endless empty documents there until memory runs out
// (jbeder/yaml-cpp#1040); a document that starts where the previous one did is that case.
void checkOneDocument(const std::string& text, const std::string& file) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentStarts starts;
  while (starts.marks.size() < 3 && parser.HandleNextDocument(starts)) {
    std::size_t n = starts.marks.size();
    if (n >= 2 && starts.marks[n - 1].pos == starts.marks[n - 2].pos) {
      throwSceneError(file, lineOf(starts.marks[n - 1]), "yaml",
                      "unexpected token (a ',' outside [ ] or { }?)");
    }
  }
  if (starts.marks.empty()) {
    throwSceneError(file, 1, "", "the file is empty; expected world, tick, seed and zones");
  }
  if (starts.marks.size() > 1) {
    throwSceneError(file, lineOf(starts.marks[1]), "",
                    "a scene file holds one YAML document, found more");
  }
}

}  // namespace

YAML::Node parseSceneDocument(const std::string& text, const std::string& file) {
  try {
    checkOneDocument(text, file);
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throwSceneError(file, lineOf(e.mark), "yaml", e.msg);
  }
}

}  // namespace zonesim
