/**
 * @class   pqMaterialNodesTrack
 * @brief   The Multi-Material Editor's node track: the nodes of a
 *          mmv::MaterialNodeModel as handles along the data range, over the
 *          opacity curve and the curve of one material parameter.
 *
 * Click on empty space adds a node, dragging moves it, Delete/Backspace
 * removes the selected one, Left/Right/Escape change the selection. The
 * track only paints and turns input into calls on its owner
 * (pqMaterialNodesPropertyWidget), which holds the state and pushes every
 * change to the property; it never changes the model itself.
 */
#ifndef pqMaterialNodesTrack_h
#define pqMaterialNodesTrack_h

#include "vtkMultiMaterialParameters.h"

#include <QString>
#include <QWidget>

#include <utility>
#include <vector>

class QPainter;
class pqMaterialNodesPropertyWidget;
namespace mmv
{
class MaterialNodeModel;
}

class pqMaterialNodesTrack : public QWidget
{
public:
  /// What the track draws besides the nodes; the owner keeps it current
  /// and calls update().
  struct ViewState
  {
    std::vector<std::pair<double, double>> Opacity; // (value, opacity) points
    int ShownParameter = mmv::Diffuse;              // whose curve is drawn
    QString ActivePreset; // a whole-range preset that replaces the nodes, or ""
  };

  pqMaterialNodesTrack(pqMaterialNodesPropertyWidget* owner, const mmv::MaterialNodeModel& model);

  ViewState& viewState() { return this->View; }

  QSize sizeHint() const override { return QSize(240, 84); }
  QSize minimumSizeHint() const override { return QSize(120, 84); }

  // Geometry: the plot (opacity and parameter curves) on top, the handle
  // strip below it, the range labels at the bottom.
  static constexpr int Radius = 5;
  QRectF plotRect() const;
  double handleY() const { return this->plotRect().bottom() + Radius + 3; }
  double toX(double value, const double range[2]) const;
  double toValue(double x, const double range[2]) const;

  // Nearest node within grabbing distance of x, -1 if none.
  int nodeAt(double x) const;

protected:
  void paintEvent(QPaintEvent*) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

private:
  // The parts of paintEvent: the filled opacity curve in the plot, and the
  // nodes' guide lines and handles.
  void paintOpacityCurve(QPainter& painter, const double range[2]) const;
  void paintHandles(QPainter& painter, const double range[2]) const;

  pqMaterialNodesPropertyWidget* Owner;
  const mmv::MaterialNodeModel& Model;
  ViewState View;
  int Dragging = -1;
  bool Moved = false;
  bool Pending = false; // node added by this press, not yet committed
  double DragRange[2] = { 0, 1 };
};

#endif
