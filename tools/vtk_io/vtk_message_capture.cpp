#include "tools/vtk_io/vtk_message_capture.hpp"

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkXMLReader.h>

#include <algorithm>

namespace tetray::vtkio {

class MessageCollector final : public vtkCommand {
 public:
  static MessageCollector* New() { return new MessageCollector; }

  void Execute(vtkObject* caller, unsigned long event, void* text) override {
    if (event != vtkCommand::ErrorEvent || !text) return;
    // An executive only repeats that its algorithm failed, with a dump of the request.
    append(static_cast<const char*>(text),
           vtkExecutive::SafeDownCast(caller) ? pipeline_ : errors_);
  }

  const std::string& errors() const { return errors_.empty() ? pipeline_ : errors_; }

 private:
  // VTK's text reads "ERROR: In <file>, line <n>\n<Class> (0x...): <message>\n\n"; keep
  // "<Class>: <message>".
  static void append(std::string message, std::string& errors) {
    if (message.rfind("ERROR: In ", 0) == 0 && message.find('\n') != std::string::npos) {
      message.erase(0, message.find('\n') + 1);
    }
    const std::size_t pointer = message.find(" (0x");
    const std::size_t pointer_end = message.find("): ", pointer);
    if (pointer != std::string::npos && pointer_end != std::string::npos) {
      message.erase(pointer, pointer_end + 1 - pointer);
    }
    message.erase(std::min(message.find('\n'), message.size()));  // the first line only
    if (message.empty()) return;
    if (!errors.empty()) errors += "; ";
    errors += message;
  }

  std::string errors_;    // from the watched readers, writers and parsers
  std::string pipeline_;  // from their executives
};

VtkMessageCapture::VtkMessageCapture() : collector_(vtkSmartPointer<MessageCollector>::New()) {}

VtkMessageCapture::~VtkMessageCapture() = default;

void VtkMessageCapture::watch(vtkObject* object) {
  object->AddObserver(vtkCommand::ErrorEvent, collector_);
  object->AddObserver(vtkCommand::WarningEvent, collector_);
}

void VtkMessageCapture::watch(vtkAlgorithm* algorithm) {
  watch(static_cast<vtkObject*>(algorithm));
  watch(algorithm->GetExecutive());
}

void VtkMessageCapture::watch(vtkXMLReader* reader) {
  watch(static_cast<vtkAlgorithm*>(reader));
  reader->SetReaderErrorObserver(collector_);
  reader->SetParserErrorObserver(collector_);
}

std::string VtkMessageCapture::errors() const { return collector_->errors(); }

}  // namespace tetray::vtkio
