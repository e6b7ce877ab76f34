// VTK reports errors by printing them (vtkOutputWindow and vtkLogger, both to stderr), not by
// return values; an object with an ErrorEvent observer sends its errors only to the observer.
// A capture observes the objects of one read or write, so that their failure becomes one clear
// error message and nothing reaches the solver's stderr uncontrolled. No global VTK state is
// touched, so other threads using VTK are not affected.
#pragma once

#include <vtkSmartPointer.h>

#include <string>

class vtkAlgorithm;
class vtkObject;
class vtkXMLReader;

namespace tetray::vtkio {

class MessageCollector;

class VtkMessageCapture {
 public:
  VtkMessageCapture();
  ~VtkMessageCapture();
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  // Errors and warnings of this object (warnings are dropped).
  void watch(vtkObject* object);
  // An algorithm and its executive.
  void watch(vtkAlgorithm* algorithm);
  // An XML reader, its executive, its XML parser and, for parallel files, its piece readers.
  void watch(vtkXMLReader* reader);

  // The collected error messages joined by "; ", without VTK's file/line/pointer decoration;
  // empty when there was none.
  std::string errors() const;

 private:
  vtkSmartPointer<MessageCollector> collector_;
};

}  // namespace tetray::vtkio
